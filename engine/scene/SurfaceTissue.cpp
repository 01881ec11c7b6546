#include "scene/SurfaceTissue.hpp"

#include <algorithm>
#include <chrono>
#include <limits>
#include <map>
#include <sstream>
#include <tuple>

#include "mesh/BoundaryFaces.hpp"
#include "mesh/CavityPoints.hpp"
#include "mesh/InterfaceSlivers.hpp"
#include "mesh/LongEdgeSplit.hpp"
#include "mesh/SurfaceCleanup.hpp"
#include "mesh/SurfaceDistance.hpp"
#include "mesh/Tetrahedralize.hpp"
#include "mesh/TissueBoolean.hpp"

namespace orthosim {
namespace {

// No boundary edge longer than this many times the skin's target edge at its place: flat patches
// (the mouth slit's walls) otherwise keep a few triangles tens of mm long, whose tetrahedra
// cannot bend (mesh/LongEdgeSplit).
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

// Flat tetrahedra on one bone (mesh/InterfaceSlivers.hpp) removed by a free node each, in up to
// three rounds (a cavity that could not be emptied may be after its neighbours were). Returns the
// report's words.
std::string splitFlatBoneTets(TetMesh& mesh, const LabelledSurface& boundary, const SurfaceTissueInput& in) {
  const auto byLabel = labelNodes(boundary, mesh, static_cast<int>(in.solids.size()) + 1);
  std::vector<std::vector<int>> bones;
  for (int b : in.bones) bones.push_back(byLabel.at(b + 1));
  std::vector<int> flat = flatTetsOnOneSet(mesh, bones, in.flatBoneDihedralDeg);
  if (flat.empty()) return "";
  std::ostringstream how;
  how << ", " << flat.size() << " flat tetrahedra on one bone";
  int added = 0;
  double worst = 180;
  for (int round = 0; round < 3 && !flat.empty(); ++round) {
    const SliverSplitReport split = splitTets(mesh, flat, bones);
    validateMesh(mesh, "splitting flat tetrahedra on the bones");
    added += split.nodesAdded;
    worst = std::min(worst, split.worstNewDeg);
    const size_t had = flat.size();
    flat = flatTetsOnOneSet(mesh, bones, in.flatBoneDihedralDeg);
    if (flat.size() >= had) break;
  }
  how << " removed by " << added << " new nodes (smallest dihedral of their tetrahedra " << worst << " deg), "
      << flat.size() << " left";
  return how.str();
}

}  // namespace

SurfaceTissue meshSurfaceTissue(const SurfaceTissueInput& in) {
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
  double boundarySeconds = since(t0), tetgenSeconds = 0;

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
    try {
      tetgen.holes = cavityPoints(candidate.surface.vertices, candidate.surface.triangles);
      out.mesh = tetrahedralize(candidate.surface.vertices, candidate.surface.triangles, tetgen);
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
    break;
  }
  if (!meshed) throw std::runtime_error(lastError);
  t0 = Clock::now();
  how << splitFlatBoneTets(out.mesh, boundary, in);
  const double splitSeconds = since(t0);
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
    << " s, boundary " << boundarySeconds << " s, tetgen " << tetgenSeconds << " s, flat bone tetrahedra "
    << splitSeconds << " s";
  out.report.push_back(s.str());
  return out;
}

}  // namespace orthosim
