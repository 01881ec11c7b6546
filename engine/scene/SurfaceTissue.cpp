#include "scene/SurfaceTissue.hpp"

#include <algorithm>
#include <chrono>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>
#include <tuple>

#include "mesh/BoundaryFaces.hpp"
#include "mesh/MeshQuality.hpp"
#include "mesh/SurfaceDistance.hpp"
#include "meshing/CavityPoints.hpp"
#include "meshing/InterfaceSlivers.hpp"
#include "meshing/LongEdgeSplit.hpp"
#include "meshing/SurfaceCleanup.hpp"
#include "meshing/Tetrahedralize.hpp"
#include "meshing/TissueBoolean.hpp"

namespace orthosim {
namespace {

// No boundary edge longer than this many times the skin's target edge at its place: flat patches
// (the mouth slit's walls) otherwise keep a few triangles tens of mm long, whose tetrahedra
// cannot bend (meshing/LongEdgeSplit).
constexpr double kMaxEdgeFactor = 3.0;

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// The skin (label-0) triangles of a labelled boundary as a mesh with one uv per vertex: a vertex
// on a texture seam appears once per uv it carries.
SurfaceMesh skinPart(const LabelledSurface& b) {
  std::map<std::tuple<int, double, double>, int> index;
  std::vector<Eigen::Vector3d> v;
  std::vector<Eigen::Vector2d> uv;
  std::vector<Eigen::Vector3i> tris;
  for (int t = 0; t < b.surface.numTriangles(); ++t) {
    if (b.label[t] != 0) continue;
    Eigen::Vector3i tri;
    for (int c = 0; c < 3; ++c) {
      const int src = b.surface.triangles(c, t);
      const Eigen::Vector2d w = b.hasUv() ? Eigen::Vector2d(b.cornerUv.col(3 * t + c)) : Eigen::Vector2d::Zero();
      const auto [it, added] = index.try_emplace({src, w.x(), w.y()}, static_cast<int>(v.size()));
      if (added) {
        v.push_back(b.surface.vertices.col(src));
        uv.push_back(w);
      }
      tri[c] = it->second;
    }
    tris.push_back(tri);
  }
  SurfaceMesh skin;
  skin.vertices.resize(3, static_cast<Eigen::Index>(v.size()));
  for (size_t i = 0; i < v.size(); ++i) skin.vertices.col(static_cast<Eigen::Index>(i)) = v[i];
  skin.triangles.resize(3, static_cast<Eigen::Index>(tris.size()));
  for (size_t i = 0; i < tris.size(); ++i) skin.triangles.col(static_cast<Eigen::Index>(i)) = tris[i];
  if (b.hasUv()) {
    skin.uv.resize(2, static_cast<Eigen::Index>(uv.size()));
    for (size_t i = 0; i < uv.size(); ++i) skin.uv.col(static_cast<Eigen::Index>(i)) = uv[i];
  }
  return skin;
}

std::vector<int> sortedUnique(std::vector<int> v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

// Nodes on each label's triangles. Input vertices know their triangles; a Steiner point TetGen put
// on the surface lies on (within rounding of) the input triangles of its label, or on an edge
// between two labels, where it belongs to both.
std::vector<std::vector<int>> labelNodes(const LabelledSurface& surface, const TetMesh& mesh, int labels) {
  std::vector<std::vector<int>> out(labels);
  const Eigen::Matrix3Xi& F = surface.surface.triangles;
  for (int t = 0; t < F.cols(); ++t)
    for (int c = 0; c < 3; ++c) out[surface.label[t]].push_back(F(c, t));
  const int inputs = surface.surface.numVertices();
  std::vector<int> steiner;
  const Eigen::Matrix3Xi faces = boundaryFaces(mesh);
  for (Eigen::Index i = 0; i < faces.size(); ++i)
    if (faces.data()[i] >= inputs) steiner.push_back(faces.data()[i]);
  steiner = sortedUnique(std::move(steiner));
  if (!steiner.empty()) {
    Eigen::Matrix3Xd points(3, steiner.size());
    for (size_t k = 0; k < steiner.size(); ++k) points.col(k) = mesh.rest.col(steiner[k]);
    const double tol = 1e-7 * (1.0 + mesh.rest.cwiseAbs().maxCoeff());
    for (int l = 0; l < labels; ++l) {
      std::vector<int> tris;
      for (int t = 0; t < F.cols(); ++t)
        if (surface.label[t] == l) tris.push_back(t);
      if (tris.empty()) continue;
      Eigen::Matrix3Xi G(3, tris.size());
      for (size_t k = 0; k < tris.size(); ++k) G.col(k) = F.col(tris[k]);
      const Eigen::VectorXd d = distancesToSurface(surface.surface.vertices, G, points);
      for (size_t k = 0; k < steiner.size(); ++k)
        if (d[k] <= tol) out[l].push_back(steiner[k]);
    }
  }
  for (auto& nodes : out) nodes = sortedUnique(std::move(nodes));
  return out;
}

// Label l > 0 is solid l - 1: a bone when `bones` lists it.
bool isBoneLabel(int label, const std::vector<int>& bones) {
  return label > 0 && std::find(bones.begin(), bones.end(), label - 1) != bones.end();
}

// Vertices on a bone: edges there are not split, since a new free node next to a bone can make a
// flat tetrahedron with three bonded ones that the first move of the bone turns over.
std::vector<bool> boneVertices(const LabelledSurface& s, const std::vector<int>& bones) {
  std::vector<bool> on(s.surface.numVertices(), false);
  for (int t = 0; t < s.surface.numTriangles(); ++t)
    if (isBoneLabel(s.label[t], bones))
      for (int c = 0; c < 3; ++c) on[s.surface.triangles(c, t)] = true;
  return on;
}

// Long edges split on the skin and air cavities only: a bone's interface moves rigidly whatever its
// triangles.
EdgeSizing freeSurfaceSizing(const SurfaceTissueInput& in, const SimplifyReport& simplified) {
  const EdgeSizing target =
      targetEdgeSizing(simplified.plainSkinTrianglesPerArea, in.interfaceDensity, in.refine, kMaxEdgeFactor);
  return [target, bones = in.bones](const Eigen::Vector3d& at, int label) {
    return isBoneLabel(label, bones) ? std::numeric_limits<double>::infinity() : target(at, label);
  };
}

// Flat tetrahedra with all four nodes on one of `sets` removed by a free node each
// (meshing/InterfaceSlivers.hpp), in up to three rounds (a cavity that could not be emptied may be
// after its neighbours were); the new nodes keep off every set in `keepOff`. Returns the report's
// words.
std::string splitFlatTets(TetMesh& mesh, const std::vector<std::vector<int>>& sets,
                          const std::vector<std::vector<int>>& keepOff, double belowDeg, const std::string& where) {
  std::vector<int> flat = flatTetsOnOneSet(mesh, sets, belowDeg);
  if (flat.empty()) return "";
  std::ostringstream how;
  how << ", " << flat.size() << " flat tetrahedra on one " << where;
  int added = 0;
  double worst = 180;
  for (int round = 0; round < 3 && !flat.empty(); ++round) {
    const SliverSplitReport split = splitTets(mesh, flat, keepOff);
    validateMeshAllowingFlat(mesh, "splitting flat tetrahedra on the " + where + "s");
    added += split.nodesAdded;
    worst = std::min(worst, split.worstNewDeg);
    const size_t had = flat.size();
    flat = flatTetsOnOneSet(mesh, sets, belowDeg);
    if (flat.size() >= had) break;
  }
  how << " removed by " << added << " new nodes (smallest dihedral of their tetrahedra " << worst << " deg), "
      << flat.size() << " left";
  return how.str();
}

// Flat tetrahedra on one bone cannot give way (every node follows the bone), so those below
// flatBoneDihedralDeg go. Elsewhere on the boundary (the skin, air cavities, where they meet a
// bone) some nodes are free; there only the nearly degenerate ones (below flatFreeDihedralDeg:
// TetGen, bound to keep a nearly planar stretch of surface or a thin gap between two surfaces,
// can fill it with a tetrahedron of no volume) go, since their deformation gradient is ill-defined.
std::string splitFlatSurfaceTets(TetMesh& mesh, const LabelledSurface& boundary, const SurfaceTissueInput& in) {
  const auto byLabel = labelNodes(boundary, mesh, static_cast<int>(in.solids.size()) + 1);
  std::vector<std::vector<int>> bones, onBoundary(1);
  for (int l = 0; l < static_cast<int>(byLabel.size()); ++l) {
    if (isBoneLabel(l, in.bones)) bones.push_back(byLabel[l]);
    onBoundary[0].insert(onBoundary[0].end(), byLabel[l].begin(), byLabel[l].end());
  }
  onBoundary[0] = sortedUnique(std::move(onBoundary[0]));
  const std::string how = splitFlatTets(mesh, bones, bones, in.flatBoneDihedralDeg, "bone");
  return how + splitFlatTets(mesh, onBoundary, bones, in.flatFreeDihedralDeg, "boundary");
}

// Below this smallest dihedral angle a tetrahedron is degenerate: its deformation gradient is
// ill-defined whatever its nodes do. The next, milder clean-up is tried; the last failure names
// where it is and which surfaces its nodes lie on.
constexpr double kDegenerateDeg = 0.1;

void requireNoDegenerateTet(const TetMesh& mesh, const LabelledSurface& boundary, const SurfaceTissueInput& in) {
  int worst = -1;
  double worstDeg = kDegenerateDeg;
  for (int e = 0; e < mesh.numTets(); ++e) {
    const auto angles = dihedralAnglesDeg(mesh, e);
    const double least = *std::min_element(angles.begin(), angles.end());
    if (least < worstDeg) worstDeg = least, worst = e;
  }
  if (worst < 0) return;
  const auto byLabel = labelNodes(boundary, mesh, static_cast<int>(in.solids.size()) + 1);
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  std::vector<std::string> on;
  for (int a = 0; a < 4; ++a) {
    const int n = mesh.tets(a, worst);
    centre += 0.25 * mesh.rest.col(n);
    for (size_t l = 0; l < byLabel.size(); ++l)
      if (std::binary_search(byLabel[l].begin(), byLabel[l].end(), n)) {
        const std::string name = l == 0 ? "skin" : in.names.at(l - 1);
        if (std::find(on.begin(), on.end(), name) == on.end()) on.push_back(name);
      }
  }
  std::ostringstream o;
  o.precision(1);
  o << std::fixed << "a tetrahedron at (" << centre.x() << ", " << centre.y() << ", " << centre.z()
    << ") is degenerate (smallest dihedral angle " << std::scientific << std::setprecision(2) << worstDeg
    << " degrees), with nodes on ";
  for (size_t k = 0; k < on.size(); ++k) o << (k ? (k + 1 == on.size() ? " and " : ", ") : "") << on[k];
  if (on.empty()) o << "no surface";
  o << ": surfaces there nearly touch or run nearly parallel (a thin gap)";
  throw std::runtime_error(o.str());
}

}  // namespace

namespace {

SurfaceTissue meshAsGiven(const SurfaceTissueInput& in) {
  SurfaceTissue out;
  auto t0 = Clock::now();
  const LabelledSurface full = subtractSurfaces(in.envelope, in.solids, in.names);
  const double booleanSeconds = since(t0);
  out.skin = skinPart(full);
  for (const auto& w : full.warnings) out.report.push_back("warning: " + w);

  t0 = Clock::now();
  std::ostringstream how;
  SimplifyOptions simplify;
  simplify.skinTriangles = in.skinTriangles;
  simplify.refine = in.refine;
  simplify.interfaceDensity = in.interfaceDensity;
  SimplifyReport simplified;
  const LabelledSurface simple = simplifySurface(full, simplify, &simplified);
  how << "simplified to " << simplified.skinTriangles << " skin + " << simplified.solidTriangles
      << " interface triangles";
  double boundarySeconds = since(t0), tetgenSeconds = 0, splitSeconds = 0;

  // Needle and cap removal, boldest first. A bolder clean-up can fold the surface onto itself
  // (TetGen refuses it) or leave faces so nearly coplanar that TetGen, bound to keep them (-Y),
  // fills them with a flat tetrahedron: each result is meshed and checked, the next, milder one
  // used on failure.
  TetgenOptions tetgen;
  tetgen.maxRadiusEdgeRatio = in.maxRadiusEdgeRatio;
  tetgen.minDihedralDeg = in.minDihedralDeg;
  tetgen.preserveSurface = in.preserveSurface;
  struct Cleanup {
    double collapseMm, needleRatio, capDeg;
  };
  // The last resort is the simplified surface as it is (collapse length 0: no clean-up).
  const Cleanup cleanups[] = {{2.0 * in.maxCollapseMm, 3.0, 140.0}, {in.maxCollapseMm, 6.0, 165.0}, {0, 0, 0}};
  LabelledSurface boundary;
  std::string lastError;
  bool meshed = false;
  for (const Cleanup& c : cleanups) {
    t0 = Clock::now();
    CleanupReport cleaned;
    LabelledSurface candidate =
        c.collapseMm > 0 ? removeSlivers(simple, c.collapseMm, c.needleRatio, c.capDeg, &cleaned) : simple;
    LongEdgeSplitReport split;
    if (simplified.plainSkinTrianglesPerArea > 0)
      candidate =
          splitLongEdges(candidate, freeSurfaceSizing(in, simplified), boneVertices(candidate, in.bones), &split);
    boundarySeconds += since(t0);
    t0 = Clock::now();
    std::string splitWords;
    try {
      tetgen.holes = cavityPoints(candidate.surface.vertices, candidate.surface.triangles);
      out.mesh = tetrahedralize(candidate.surface.vertices, candidate.surface.triangles, tetgen);
      validateMeshAllowingFlat(out.mesh, "tetrahedralize");
      tetgenSeconds += since(t0);
      t0 = Clock::now();
      splitWords = splitFlatSurfaceTets(out.mesh, candidate, in);
      splitSeconds += since(t0);
      t0 = Clock::now();
      requireNoDegenerateTet(out.mesh, candidate, in);
      validateMesh(out.mesh, "tetrahedralize");
      meshed = true;
    } catch (const std::exception& e) {
      lastError = e.what();
    }
    tetgenSeconds += since(t0);
    if (!meshed) continue;
    boundary = std::move(candidate);
    if (split.splits > 0) how << ", " << split.splits << " long edges split";
    if (c.collapseMm > 0)
      how << ", needles and caps " << cleaned.needlesAndCapsBefore << " -> " << cleaned.needlesAndCapsAfter
          << " (edges collapsed up to " << c.collapseMm << " mm)";
    else
      how << ", no needle and cap removal (every clean-up failed: " << lastError << ")";
    how << splitWords;
    break;
  }
  if (!meshed) throw std::runtime_error(lastError);
  int skin = 0;
  for (int l : boundary.label) skin += l == 0;
  out.skinTriangles = skin;
  how << "; " << boundary.surface.numTriangles() << " boundary triangles, " << skin << " skin";
  for (const auto& w : boundary.warnings) out.report.push_back("warning: " + w);

  const std::vector<std::vector<int>> byLabel = labelNodes(boundary, out.mesh, static_cast<int>(in.solids.size()) + 1);
  out.skinNodes = byLabel[0];
  out.solidNodes.assign(byLabel.begin() + 1, byLabel.end());
  std::ostringstream s;
  s << "boundary: " << full.surface.numTriangles() << " triangles at full resolution (" << out.skin.numTriangles()
    << " skin), " << how.str() << "; " << tetgen.holes.cols() << " enclosed cavities; boolean " << booleanSeconds
    << " s, boundary " << boundarySeconds << " s, tetgen " << tetgenSeconds << " s, flat tetrahedra " << splitSeconds
    << " s";
  out.report.push_back(s.str());
  return out;
}

// The air cavities shifted by `mm` along a fixed oblique direction: bones and skin stay.
SurfaceTissueInput withCavitiesShifted(const SurfaceTissueInput& in, double mm) {
  SurfaceTissueInput shifted = in;
  const Eigen::Vector3d direction = Eigen::Vector3d(0.36, 0.48, 0.8).normalized();
  for (size_t k = 0; k < shifted.solids.size(); ++k)
    if (std::find(in.bones.begin(), in.bones.end(), static_cast<int>(k)) == in.bones.end())
      shifted.solids[k].vertices.colwise() += mm * direction;
  return shifted;
}

}  // namespace

// Where an air cavity runs within a fraction of a millimetre of a bone or the skin (the mouth
// slit through closed lips, the vestibule along the teeth), whether TetGen, bound to keep the
// surfaces, leaves a tetrahedron of no volume turns on rounding-level details of the surfaces. So
// when every clean-up fails, the cavities (air, whose exact place within a tenth of a millimetre
// carries nothing) are shifted by kCavityShiftMm, then twice and three times that, and meshed
// again; the report says so. Bones and skin are never moved.
SurfaceTissue meshSurfaceTissue(const SurfaceTissueInput& in) {
  constexpr double kCavityShiftMm = 0.1;
  const bool cavities = in.solids.size() > in.bones.size();
  std::string firstError;
  for (int attempt = 0; attempt < (cavities ? 4 : 1); ++attempt) {
    try {
      if (attempt == 0) return meshAsGiven(in);
      SurfaceTissue out = meshAsGiven(withCavitiesShifted(in, attempt * kCavityShiftMm));
      std::ostringstream note;
      note << "warning: the air cavities were shifted " << attempt * kCavityShiftMm
           << " mm to mesh (as given: " << firstError << ")";
      out.report.insert(out.report.begin(), note.str());
      return out;
    } catch (const std::exception& e) {
      if (attempt == 0) firstError = e.what();
      if (!cavities || attempt == 3)
        throw std::runtime_error(firstError + (attempt ? " (and with the air cavities "
                                                         "shifted up to 0.3 mm)"
                                                       : ""));
    }
  }
  throw std::logic_error("meshSurfaceTissue: unreachable");
}

}  // namespace orthosim
