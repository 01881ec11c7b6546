#include "scene/TissueCache.hpp"

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "system/AtomicFile.hpp"

namespace orthosim {
namespace {

constexpr char kMagic[8] = {'O', 'S', 'T', 'I', 'S', 'S', '0', '2'};

class Writer {
 public:
  explicit Writer(std::ostream& out) : out_(out) {}
  void i64(std::int64_t v) { out_.write(reinterpret_cast<const char*>(&v), sizeof v); }
  void f64(double v) { out_.write(reinterpret_cast<const char*>(&v), sizeof v); }
  template <class M>
  void matrix(const M& m) {
    i64(m.rows());
    i64(m.cols());
    out_.write(reinterpret_cast<const char*>(m.data()),
               static_cast<std::streamsize>(sizeof(typename M::Scalar) * m.size()));
  }
  void ints(const std::vector<int>& v) {
    i64(static_cast<std::int64_t>(v.size()));
    out_.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(sizeof(int) * v.size()));
  }
  void text(const std::string& s) {
    i64(static_cast<std::int64_t>(s.size()));
    out_.write(s.data(), static_cast<std::streamsize>(s.size()));
  }

 private:
  std::ostream& out_;
};

// Every read is bounds-checked against the file size, so a damaged file fails cleanly.
class Reader {
 public:
  Reader(std::ifstream& in, std::int64_t size) : in_(in), left_(size) {}
  std::int64_t i64() {
    std::int64_t v;
    raw(&v, sizeof v);
    return v;
  }
  double f64() {
    double v;
    raw(&v, sizeof v);
    return v;
  }
  template <class M>
  void matrix(M& m, std::int64_t rows) {
    const std::int64_t r = i64(), c = i64();
    if (r != rows || c < 0 || c * r * static_cast<std::int64_t>(sizeof(typename M::Scalar)) > left_)
      throw std::runtime_error("bad matrix");
    m.resize(r, c);
    raw(m.data(), sizeof(typename M::Scalar) * m.size());
  }
  std::vector<int> ints() {
    const std::int64_t n = i64();
    if (n < 0 || n * static_cast<std::int64_t>(sizeof(int)) > left_) throw std::runtime_error("bad list");
    std::vector<int> v(static_cast<size_t>(n));
    raw(v.data(), sizeof(int) * v.size());
    return v;
  }
  std::string text() {
    const std::int64_t n = i64();
    if (n < 0 || n > left_) throw std::runtime_error("bad text");
    std::string s(static_cast<size_t>(n), '\0');
    raw(s.data(), s.size());
    return s;
  }

 private:
  void raw(void* p, size_t n) {
    if (static_cast<std::int64_t>(n) > left_ || !in_.read(static_cast<char*>(p), static_cast<std::streamsize>(n)))
      throw std::runtime_error("truncated");
    left_ -= static_cast<std::int64_t>(n);
  }
  std::ifstream& in_;
  std::int64_t left_;
};

}  // namespace

void writeTissueCache(const std::string& path, const CaseTissue& t) {
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  AtomicFile file(path);  // a failed write (a full disk) leaves no temporary file behind
  std::ostream& out = file.out();
  out.write(kMagic, sizeof kMagic);
  Writer w(out);
  w.matrix(t.mesh.rest);
  w.matrix(t.mesh.tets);
  w.i64(static_cast<std::int64_t>(t.boneNodes.size()));
  for (const auto& b : t.boneNodes) w.ints(b);
  w.ints(t.skinNodes);
  w.i64(t.skinTriangles);
  w.matrix(t.skin.vertices);
  w.matrix(t.skin.triangles);
  w.matrix(t.skin.uv);
  const MeshQuality& q = t.quality;
  for (double v : {double(q.nodes), double(q.tets), double(q.boundaryFaces), q.minDihedralDeg, q.maxDihedralDeg,
                   q.maxRadiusEdgeRatio, q.meanRadiusEdgeRatio, q.minVolume})
    w.f64(v);
  w.i64(static_cast<std::int64_t>(t.report.size()));
  for (const auto& line : t.report) w.text(line);
  file.commit();
}

std::optional<CaseTissue> readTissueCache(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return std::nullopt;
  const std::int64_t size = in.tellg();
  in.seekg(0);
  char magic[sizeof kMagic];
  if (size < static_cast<std::int64_t>(sizeof magic) || !in.read(magic, sizeof magic) ||
      !std::equal(magic, magic + sizeof magic, kMagic))
    return std::nullopt;
  try {
    Reader r(in, size - static_cast<std::int64_t>(sizeof magic));
    CaseTissue t;
    r.matrix(t.mesh.rest, 3);
    r.matrix(t.mesh.tets, 4);
    const std::int64_t bones = r.i64();
    if (bones < 0 || bones > 1000) return std::nullopt;
    for (std::int64_t b = 0; b < bones; ++b) t.boneNodes.push_back(r.ints());
    t.skinNodes = r.ints();
    t.skinTriangles = static_cast<int>(r.i64());
    r.matrix(t.skin.vertices, 3);
    r.matrix(t.skin.triangles, 3);
    r.matrix(t.skin.uv, 2);
    MeshQuality& q = t.quality;
    q.nodes = static_cast<int>(r.f64());
    q.tets = static_cast<int>(r.f64());
    q.boundaryFaces = static_cast<int>(r.f64());
    q.minDihedralDeg = r.f64();
    q.maxDihedralDeg = r.f64();
    q.maxRadiusEdgeRatio = r.f64();
    q.meanRadiusEdgeRatio = r.f64();
    q.minVolume = r.f64();
    const std::int64_t lines = r.i64();
    if (lines < 0 || lines > 10000) return std::nullopt;
    for (std::int64_t i = 0; i < lines; ++i) t.report.push_back(r.text());
    // Indices must be in range: a damaged file must not reach the solver.
    const int n = t.mesh.numNodes();
    if ((t.mesh.tets.size() && (t.mesh.tets.minCoeff() < 0 || t.mesh.tets.maxCoeff() >= n)) ||
        (t.skin.triangles.size() &&
         (t.skin.triangles.minCoeff() < 0 || t.skin.triangles.maxCoeff() >= t.skin.numVertices())))
      return std::nullopt;
    for (const auto& b : t.boneNodes)
      for (int i : b)
        if (i < 0 || i >= n) return std::nullopt;
    for (int i : t.skinNodes)
      if (i < 0 || i >= n) return std::nullopt;
    if (t.skin.uv.cols() != 0 && t.skin.uv.cols() != t.skin.vertices.cols()) return std::nullopt;
    return t;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

}  // namespace orthosim
