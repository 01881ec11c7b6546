// Compiled with -DTETLIBRARY (engine/CMakeLists.txt): tetgen.h declares tetrahedralize(switches,
// in, out) only then, and its error exit throws an int instead of calling exit().
#include "meshing/Tetrahedralize.hpp"

#include <dlfcn.h>
#include <tetgen.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <mutex>
#include <new>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <vector>

#include "mesh/BoundaryFaces.hpp"

namespace orthosim {
namespace detail {
void* tetgenTerminateOverride();  // meshing/TetgenTerminate.cpp
}

namespace {

using Key = std::array<int, 3>;  // a triangle's vertices, sorted

Key sortedKey(int a, int b, int c) {
  Key k{a, b, c};
  std::sort(k.begin(), k.end());
  return k;
}

[[noreturn]] void fail(const std::string& what) { throw std::runtime_error("tetrahedralize: " + what); }

std::string point(const Eigen::Vector3d& x) {
  std::ostringstream s;
  s << "(" << x.x() << ", " << x.y() << ", " << x.z() << ")";
  return s.str();
}

// Everything TetGen would misread or reject obscurely, named precisely before it runs.
void checkSurface(const Eigen::Matrix3Xd& V, const Eigen::Matrix3Xi& T) {
  const int n = static_cast<int>(V.cols()), m = static_cast<int>(T.cols());
  if (m == 0) fail("the surface has no triangles");
  for (int i = 0; i < n; ++i)
    if (!V.col(i).allFinite()) fail("vertex " + std::to_string(i) + " has a non-finite coordinate");
  std::vector<char> used(n, 0);
  for (int t = 0; t < m; ++t) {
    for (int a = 0; a < 3; ++a) {
      const int v = T(a, t);
      if (v < 0 || v >= n)
        fail("triangle " + std::to_string(t) + " refers to vertex " + std::to_string(v) + ", outside 0.." +
             std::to_string(n - 1));
      used[v] = 1;
      if (T((a + 1) % 3, t) == v) fail("triangle " + std::to_string(t) + " repeats vertex " + std::to_string(v));
    }
    const Eigen::Vector3d e1 = V.col(T(1, t)) - V.col(T(0, t)), e2 = V.col(T(2, t)) - V.col(T(0, t));
    const double longest2 = std::max({e1.squaredNorm(), e2.squaredNorm(), (e2 - e1).squaredNorm()});
    if (e1.cross(e2).norm() <= 1e-12 * longest2)
      fail("triangle " + std::to_string(t) + " is degenerate (its vertices are collinear)");
  }
  for (int i = 0; i < n; ++i)
    if (!used[i]) fail("vertex " + std::to_string(i) + " belongs to no triangle (TetGen would drop it and renumber)");

  // Coincident vertices: TetGen would merge them and renumber the rest.
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  auto less = [&](int a, int b) {
    return std::lexicographical_compare(V.col(a).data(), V.col(a).data() + 3, V.col(b).data(), V.col(b).data() + 3);
  };
  std::sort(order.begin(), order.end(), less);
  for (int k = 1; k < n; ++k)
    if (V.col(order[k]) == V.col(order[k - 1]))
      fail("vertices " + std::to_string(std::min(order[k], order[k - 1])) + " and " +
           std::to_string(std::max(order[k], order[k - 1])) + " coincide at " + point(V.col(order[k])));

  // Closed, edge-manifold and consistently oriented: every edge a -> b of a triangle is matched by
  // exactly one b -> a of another.
  struct HalfEdge {
    int lo, hi, tri;
    bool forward;  // runs lo -> hi
  };
  std::vector<HalfEdge> halves;
  halves.reserve(3 * static_cast<size_t>(m));
  for (int t = 0; t < m; ++t)
    for (int a = 0; a < 3; ++a) {
      const int u = T(a, t), v = T((a + 1) % 3, t);
      halves.push_back({std::min(u, v), std::max(u, v), t, u < v});
    }
  std::sort(halves.begin(), halves.end(), [](const HalfEdge& a, const HalfEdge& b) {
    return std::tie(a.lo, a.hi, a.tri) < std::tie(b.lo, b.hi, b.tri);
  });
  for (size_t i = 0; i < halves.size();) {
    size_t j = i;
    while (j < halves.size() && halves[j].lo == halves[i].lo && halves[j].hi == halves[i].hi) ++j;
    const std::string edge = "edge (" + std::to_string(halves[i].lo) + ", " + std::to_string(halves[i].hi) + ")";
    if (j - i == 1) fail("the surface is open: " + edge + " belongs only to triangle " + std::to_string(halves[i].tri));
    if (j - i > 2) {
      std::string tris;
      for (size_t k = i; k < j; ++k) tris += (k > i ? ", " : "") + std::to_string(halves[k].tri);
      fail("the surface is not manifold: " + edge + " belongs to " + std::to_string(j - i) + " triangles (" + tris +
           ")");
    }
    if (halves[i].forward == halves[i + 1].forward)
      fail("the surface is inconsistently oriented: triangles " + std::to_string(halves[i].tri) + " and " +
           std::to_string(halves[i + 1].tri) + " run " + edge + " the same way");
    i = j;
  }
}

// Debian's libtet crashes on its own errors unless meshing/TetgenTerminate.cpp replaced its error
// exit; make sure it did before handing TetGen anything.
void requireTerminateOverride() {
  static const bool ok = dlsym(RTLD_DEFAULT, "_Z15terminatetetgenP10tetgenmeshi") == detail::tetgenTerminateOverride();
  if (!ok)
    fail(
        "TetGen's error exit terminatetetgen() does not resolve to meshing/TetgenTerminate.cpp, so any TetGen error "
        "would crash the process (double free in libtet 1.5.0); refusing to run TetGen");
}

void fillPlc(tetgenio& in, const Eigen::Matrix3Xd& V, const Eigen::Matrix3Xi& T, const Eigen::Matrix3Xd& holes) {
  in.firstnumber = 0;
  in.numberofpoints = static_cast<int>(V.cols());
  in.pointlist = new REAL[3 * V.cols()];
  for (int i = 0; i < V.cols(); ++i)
    for (int a = 0; a < 3; ++a) in.pointlist[3 * i + a] = V(a, i);
  // One facet per triangle; tetgenio's destructor frees all of it.
  in.numberoffacets = static_cast<int>(T.cols());
  in.facetlist = new tetgenio::facet[T.cols()];
  for (int t = 0; t < T.cols(); ++t) {
    tetgenio::facet& f = in.facetlist[t];
    tetgenio::init(&f);
    f.numberofpolygons = 1;
    f.polygonlist = new tetgenio::polygon[1];
    tetgenio::init(&f.polygonlist[0]);
    f.polygonlist[0].numberofvertices = 3;
    f.polygonlist[0].vertexlist = new int[3];
    for (int a = 0; a < 3; ++a) f.polygonlist[0].vertexlist[a] = T(a, t);
  }
  if (holes.cols() > 0) {
    in.numberofholes = static_cast<int>(holes.cols());
    in.holelist = new REAL[3 * holes.cols()];
    for (int h = 0; h < holes.cols(); ++h)
      for (int a = 0; a < 3; ++a) in.holelist[3 * h + a] = holes(a, h);
  }
}

// Runs TetGen; returns its error code, 0 on success.
int runTetgen(const std::string& switches, tetgenio& in, tetgenio& out) {
  std::vector<char> s(switches.begin(), switches.end());
  s.push_back('\0');
  try {
    tetrahedralize(s.data(), &in, &out);
  } catch (int code) {
    return code == 0 ? -1 : code;
  } catch (const std::bad_alloc&) {
    return 1;  // as TetGen's own out-of-memory code
  }
  return 0;
}

// TetGen's -d lists the facets that intersect; map them back to input triangles.
std::string intersectingTriangles(tetgenio& in, const Eigen::Matrix3Xi& T) {
  tetgenio diag;
  if (runTetgen("pdMQ", in, diag) != 0 || diag.numberoftrifaces == 0) return "";
  std::map<Key, int> index;
  for (int t = 0; t < T.cols(); ++t) index.emplace(sortedKey(T(0, t), T(1, t), T(2, t)), t);
  std::vector<int> tris;
  for (int f = 0; f < diag.numberoftrifaces; ++f) {
    const int* c = diag.trifacelist + 3 * f;
    const int b = diag.firstnumber;
    const auto it = index.find(sortedKey(c[0] - b, c[1] - b, c[2] - b));
    if (it != index.end()) tris.push_back(it->second);
  }
  std::sort(tris.begin(), tris.end());
  tris.erase(std::unique(tris.begin(), tris.end()), tris.end());
  if (tris.empty()) return "";
  std::string list;
  const size_t shown = std::min<size_t>(tris.size(), 12);
  for (size_t k = 0; k < shown; ++k) list += (k ? ", " : "") + std::to_string(tris[k]);
  if (shown < tris.size()) list += ", ... (" + std::to_string(tris.size()) + " in all)";
  return " (triangles " + list + ")";
}

// TetGen 1.5's error codes, as its terminatetetgen() explains them.
std::string tetgenError(int code, tetgenio& in, const Eigen::Matrix3Xi& T) {
  switch (code) {
    case 1:
      return "TetGen ran out of memory";
    case 2:
      return "TetGen hit an internal error (a TetGen bug; the surface may be nearly degenerate)";
    case 3:
      return "the surface intersects itself" + intersectingTriangles(in, T);
    case 4:
      return "TetGen found a very small input feature (a vertex almost on an edge or triangle it is not part of)";
    case 5:
      return "TetGen found two nearly coincident triangles";
    case 10:
      return "TetGen rejected the input";
    default:
      return "TetGen failed with error code " + std::to_string(code);
  }
}

std::string fixedNumber(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6f", x);  // TetGen reads -q values as digits and '.', no exponent
  return buf;
}

std::mutex& tetgenMutex() {
  static std::mutex m;
  return m;
}

}  // namespace

std::string tetgenSwitches(const TetgenOptions& o) {
  const double ratio = o.maxRadiusEdgeRatio, angle = o.minDihedralDeg;
  if (!(ratio == 0 || (ratio >= 1.0 && std::isfinite(ratio))))
    fail("maxRadiusEdgeRatio must be 0 (no refinement) or at least 1 (TetGen may not terminate below), got " +
         std::to_string(ratio));
  if (!(angle >= 0 && angle < 70))
    fail("minDihedralDeg must be in [0, 70) degrees (a regular tet has 70.5), got " + std::to_string(angle));
  if (angle > 0 && ratio == 0) fail("minDihedralDeg needs quality refinement (maxRadiusEdgeRatio > 0)");
  if (!(o.maxVolume >= 0 && std::isfinite(o.maxVolume)))
    fail("maxVolume must be 0 (none) or a positive volume in mm^3, got " + std::to_string(o.maxVolume));
  for (int h = 0; h < o.holes.cols(); ++h)
    if (!o.holes.col(h).allFinite()) fail("hole point " + std::to_string(h) + " has a non-finite coordinate");

  std::string s = "p";
  if (ratio > 0) {
    s += "q" + fixedNumber(ratio);
    if (angle > 0) s += "/" + fixedNumber(angle);
  }
  if (o.maxVolume > 0) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "a%.17g", o.maxVolume);  // -a accepts exponents
    s += buf;
  }
  if (o.preserveSurface) s += "YM";
  if (o.quiet) s += "Q";
  return s;
}

TetMesh tetrahedralize(const Eigen::Matrix3Xd& vertices, const Eigen::Matrix3Xi& triangles,
                       const TetgenOptions& options, MeshQuality* quality) {
  const std::string switches = tetgenSwitches(options);
  checkSurface(vertices, triangles);
  requireTerminateOverride();
  const int n = static_cast<int>(vertices.cols());

  tetgenio in, out;
  fillPlc(in, vertices, triangles, options.holes);
  {
    std::lock_guard<std::mutex> lock(tetgenMutex());  // TetGen keeps global state (its predicates)
    if (const int code = runTetgen(switches, in, out))
      fail(tetgenError(code, in, triangles) + " [TetGen -" + switches + "]");
  }
  const std::string where = " [TetGen -" + switches + "]";
  if (out.numberoftetrahedra == 0)
    fail("TetGen produced no tetrahedra: the surface encloses no volume (or the holes empty all of it)" + where);
  if (out.numberofcorners != 4)
    fail("TetGen produced " + std::to_string(out.numberofcorners) + "-node elements" + where);
  if (out.numberofpoints < n) fail("TetGen returned fewer nodes than input vertices" + where);

  TetMesh mesh;
  mesh.rest.resize(3, out.numberofpoints);
  for (int i = 0; i < out.numberofpoints; ++i)
    for (int a = 0; a < 3; ++a) mesh.rest(a, i) = out.pointlist[3 * i + a];
  for (int i = 0; i < n; ++i)
    if (mesh.rest.col(i) != vertices.col(i))
      fail("TetGen moved or renumbered input vertex " + std::to_string(i) + " (now " + point(mesh.rest.col(i)) + ")" +
           where);

  mesh.tets.resize(4, out.numberoftetrahedra);
  for (int e = 0; e < out.numberoftetrahedra; ++e) {
    for (int a = 0; a < 4; ++a) {
      const int v = out.tetrahedronlist[4 * e + a] - out.firstnumber;
      if (v < 0 || v >= mesh.numNodes())
        fail("TetGen element " + std::to_string(e) + " refers to a missing node" + where);
      mesh.tets(a, e) = v;
    }
    // TetGen orients tets as orthosim does (det[x1-x0, x2-x0, x3-x0] > 0, checked by the tests);
    // a sliver whose rounded determinant disagrees with TetGen's exact predicate is flipped.
    const double v = mesh.signedVolume(e, mesh.rest);
    if (v < 0) std::swap(mesh.tets(1, e), mesh.tets(2, e));
    if (v == 0) fail("TetGen produced a flat tetrahedron (element " + std::to_string(e) + ")" + where);
  }

  if (options.preserveSurface) {
    // Later code embeds the skin in the surface tets: hold TetGen to its -Y promise. Every input
    // triangle is a face of the mesh (a cavity without a hole point leaves its surface inside),
    // and every boundary face is an input triangle.
    std::vector<Key> faces;
    faces.reserve(4 * static_cast<size_t>(mesh.numTets()));
    for (int e = 0; e < mesh.numTets(); ++e)
      for (int a = 0; a < 4; ++a)
        faces.push_back(sortedKey(mesh.tets((a + 1) % 4, e), mesh.tets((a + 2) % 4, e), mesh.tets((a + 3) % 4, e)));
    std::sort(faces.begin(), faces.end());
    std::vector<Key> input;
    for (int t = 0; t < triangles.cols(); ++t) {
      input.push_back(sortedKey(triangles(0, t), triangles(1, t), triangles(2, t)));
      if (!std::binary_search(faces.begin(), faces.end(), input.back()))
        fail("TetGen split the surface despite -Y: triangle " + std::to_string(t) + " is not a face of the mesh" +
             where);
    }
    std::sort(input.begin(), input.end());
    const Eigen::Matrix3Xi boundary = boundaryFaces(mesh);
    for (int f = 0; f < boundary.cols(); ++f)
      if (!std::binary_search(input.begin(), input.end(), sortedKey(boundary(0, f), boundary(1, f), boundary(2, f))))
        fail("TetGen split the surface despite -Y: boundary face (" + std::to_string(boundary(0, f)) + ", " +
             std::to_string(boundary(1, f)) + ", " + std::to_string(boundary(2, f)) + ") is not an input triangle" +
             where);
  }
  if (quality) *quality = measureQuality(mesh);
  return mesh;
}

}  // namespace orthosim
