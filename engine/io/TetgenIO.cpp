#include "io/TetgenIO.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace orthosim {
namespace {

// Reads non-empty, non-comment lines ('#' starts a comment), keeping line numbers for errors.
struct LineReader {
  std::ifstream in;
  std::string path;
  int lineNo = 0;

  explicit LineReader(const std::string& p) : in(p), path(p) {
    if (!in) throw std::runtime_error(path + ": cannot open file");
  }
  bool next(std::istringstream& out) {
    std::string line;
    while (std::getline(in, line)) {
      ++lineNo;
      const auto hash = line.find('#');
      if (hash != std::string::npos) line.resize(hash);
      if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
      out.clear();
      out.str(line);
      return true;
    }
    return false;
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error(path + ":" + std::to_string(lineNo) + ": " + what);
  }
};

double readCoordinate(std::istringstream& s, LineReader& r, const char* axis) {
  std::string tok;
  if (!(s >> tok)) r.fail(std::string("missing ") + axis + " coordinate");
  char* end = nullptr;
  const double v = std::strtod(tok.c_str(), &end);
  if (end == tok.c_str() || *end != '\0') r.fail(std::string("bad ") + axis + " coordinate '" + tok + "'");
  if (!std::isfinite(v)) r.fail(std::string("non-finite ") + axis + " coordinate '" + tok + "'");
  return v;
}

}  // namespace

TetgenMesh readTetgen(const std::string& nodePath, const std::string& elePath) {
  TetgenMesh out;
  std::istringstream s;
  {
    LineReader r(nodePath);
    if (!r.next(s)) r.fail("empty .node file");
    long n = 0, dim = 0;
    if (!(s >> n >> dim) || n <= 0) r.fail("bad header: expected '<#points> 3 <#attributes> <#markers>'");
    if (dim != 3) r.fail("dimension is " + std::to_string(dim) + ", expected 3");
    out.mesh.rest.resize(3, n);
    for (long i = 0; i < n; ++i) {
      if (!r.next(s)) r.fail("file ends after " + std::to_string(i) + " of " + std::to_string(n) + " nodes");
      long id = 0;
      if (!(s >> id)) r.fail("bad node index");
      if (i == 0) {
        if (id != 0 && id != 1) r.fail("first node index is " + std::to_string(id) + ", expected 0 or 1");
        out.indexBase = static_cast<int>(id);
      }
      if (id != i + out.indexBase)
        r.fail("node index " + std::to_string(id) + " out of sequence, expected " + std::to_string(i + out.indexBase));
      out.mesh.rest(0, i) = readCoordinate(s, r, "x");
      out.mesh.rest(1, i) = readCoordinate(s, r, "y");
      out.mesh.rest(2, i) = readCoordinate(s, r, "z");
    }
  }
  {
    LineReader r(elePath);
    if (!r.next(s)) r.fail("empty .ele file");
    long m = 0, per = 0;
    if (!(s >> m >> per) || m <= 0) r.fail("bad header: expected '<#tetrahedra> 4 <#attributes>'");
    if (per != 4) r.fail(std::to_string(per) + " nodes per tetrahedron; only linear (4-node) tetrahedra are supported");
    out.mesh.tets.resize(4, m);
    const long n = out.mesh.numNodes();
    for (long e = 0; e < m; ++e) {
      if (!r.next(s)) r.fail("file ends after " + std::to_string(e) + " of " + std::to_string(m) + " tetrahedra");
      long id = 0;
      if (!(s >> id)) r.fail("bad element index");
      for (int a = 0; a < 4; ++a) {
        long v = 0;
        if (!(s >> v)) r.fail("element " + std::to_string(id) + " has fewer than 4 node indices");
        const long i = v - out.indexBase;
        if (i < 0 || i >= n)
          r.fail("element " + std::to_string(id) + " refers to node " + std::to_string(v) + ", outside " +
                 std::to_string(out.indexBase) + ".." + std::to_string(n - 1 + out.indexBase));
        out.mesh.tets(a, e) = static_cast<int>(i);
      }
    }
  }
  return out;
}

void writeTetgenNodes(const std::string& path, const Eigen::Matrix3Xd& x, int indexBase) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw std::runtime_error(path + ": cannot write file");
  std::fprintf(f, "%ld 3 0 0\n", static_cast<long>(x.cols()));
  for (long i = 0; i < x.cols(); ++i)
    std::fprintf(f, "%ld %.17g %.17g %.17g\n", i + indexBase, x(0, i), x(1, i), x(2, i));
  const bool ok = std::fclose(f) == 0;
  if (!ok) throw std::runtime_error(path + ": write failed");
}

void writeTetgenElements(const std::string& path, const Eigen::Matrix4Xi& tets, int indexBase) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw std::runtime_error(path + ": cannot write file");
  std::fprintf(f, "%ld 4 0\n", static_cast<long>(tets.cols()));
  for (long e = 0; e < tets.cols(); ++e)
    std::fprintf(f, "%ld %d %d %d %d\n", e + indexBase, tets(0, e) + indexBase, tets(1, e) + indexBase,
                 tets(2, e) + indexBase, tets(3, e) + indexBase);
  const bool ok = std::fclose(f) == 0;
  if (!ok) throw std::runtime_error(path + ": write failed");
}

}  // namespace orthosim
