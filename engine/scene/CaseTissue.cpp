#include "scene/CaseTissue.hpp"

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>
#include <variant>

#include "io/SurfaceImport.hpp"
#include "io/TetgenIO.hpp"
#include "mesh/BoundaryFaces.hpp"
#include "mesh/SurfaceCheck.hpp"
#include "meshing/SurfaceRules.hpp"
#include "scene/BoneContact.hpp"
#include "scene/SceneFields.hpp"
#include "scene/SurfaceTissue.hpp"
#include "scene/TissueCache.hpp"
#include "system/FileLock.hpp"

namespace orthosim {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// FNV-1a, 64 bit: a stable content hash (the key must not change between runs or machines).
struct Hash {
  std::uint64_t h = 1469598103934665603ull;
  void bytes(const char* p, size_t n) {
    for (size_t i = 0; i < n; ++i) h = (h ^ static_cast<unsigned char>(p[i])) * 1099511628211ull;
  }
  void text(const std::string& s) {
    bytes(s.data(), s.size());
    bytes("\0", 1);
  }
  void number(double v) { text(std::to_string(v)); }
  void file(const std::string& path, const std::string& field) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw SceneError(field + ": cannot open '" + path + "'");
    std::ostringstream ss;
    ss << in.rdbuf();
    text(ss.str());
  }
};

void say(CaseTissue& t, const CaseTissueOptions& o, const std::string& line) {
  t.report.push_back(line);
  if (o.verbose) std::cout << line << std::endl;
}

std::string qualityLine(const MeshQuality& q) {
  std::ostringstream s;
  s << std::setprecision(3) << q.nodes << " nodes, " << q.tets << " tets, " << q.boundaryFaces
    << " boundary triangles; dihedral angles " << q.minDihedralDeg << "-" << q.maxDihedralDeg
    << " deg, radius-edge ratio max " << q.maxRadiusEdgeRatio << " mean " << q.meanRadiusEdgeRatio;
  return s.str();
}

// Boundary nodes of the mesh: the default candidates for a bone's bonded group.
std::vector<int> boundaryNodes(const TetMesh& mesh) {
  const Eigen::Matrix3Xi faces = boundaryFaces(mesh);
  std::vector<char> on(mesh.numNodes(), 0);
  for (Eigen::Index i = 0; i < faces.size(); ++i) on[faces.data()[i]] = 1;
  std::vector<int> out;
  for (int i = 0; i < mesh.numNodes(); ++i)
    if (on[i]) out.push_back(i);
  return out;
}

// A surface of the case, checked; skin and bones by the rule import applied (meshing/SurfaceRules), so
// that what import accepted is accepted here, repaired the same way if it was written unrepaired.
SurfaceMesh readSurface(const CaseSpec& spec, const std::string& path, const std::string& field,
                        const std::variant<SurfaceRequirement, SurfaceRole>& rule, CaseTissue& t,
                        const CaseTissueOptions& o) {
  try {
    SurfaceMesh m = importSurface(path);
    const std::string name = fs::path(path).filename().string();
    const SurfaceReport r = std::holds_alternative<SurfaceRole>(rule)
                                ? repairAndCheck(m, name, std::get<SurfaceRole>(rule))
                                : checkSurface(m, name, std::get<SurfaceRequirement>(rule));
    for (const auto& w : r.warnings) say(t, o, "warning: " + w);
    return m;
  } catch (const SceneError&) {
    throw;
  } catch (const std::exception& e) {
    throw SceneError(spec.file + ": " + field + ": " + e.what());
  }
}

CaseTissue volumeTissue(const CaseSpec& spec, const CaseTissueOptions& o) {
  CaseTissue t;
  try {
    TetgenMesh m = readTetgen(spec.node, spec.ele);
    t.mesh = std::move(m.mesh);
    t.indexBase = m.indexBase;
    validateMesh(t.mesh, spec.ele, t.indexBase);
  } catch (const std::exception& e) {
    throw SceneError(spec.file + ": tissue: " + e.what());
  }
  const int n = t.mesh.numNodes();
  // Node sets first: a derived group never takes a node that a node set gives to another bone.
  std::vector<int> claimedBy(n, -1);
  t.boneNodes.resize(spec.bones.size());
  for (size_t b = 0; b < spec.bones.size(); ++b) {
    const CaseBone& bone = spec.bones[b];
    if (bone.nodes.empty()) continue;
    t.boneNodes[b] = readNodeSet(bone.nodes, n, "bones[" + std::to_string(b) + "].nodes");
    for (int i : t.boneNodes[b]) claimedBy[i] = static_cast<int>(b);
    say(t, o,
        bone.name + ": " + std::to_string(t.boneNodes[b].size()) + " bonded nodes from " +
            fs::path(bone.nodes).filename().string());
  }
  std::vector<int> boundary;
  for (size_t b = 0; b < spec.bones.size(); ++b) {
    const CaseBone& bone = spec.bones[b];
    if (!bone.derive) continue;
    const std::string field = "bones[" + std::to_string(b) + "]";
    const SurfaceMesh surface =
        readSurface(spec, bone.surface, field + ".surface", SurfaceRequirement::OpenAllowed, t, o);
    std::vector<int> candidates;
    if (!bone.candidates.empty()) {
      candidates = readNodeSet(bone.candidates, n, field + ".candidates");
    } else {
      if (boundary.empty()) boundary = boundaryNodes(t.mesh);
      candidates = boundary;
    }
    std::vector<int> open;
    for (int i : candidates)
      if (claimedBy[i] < 0 || claimedBy[i] == static_cast<int>(b)) open.push_back(i);
    const BoneContact c = nodesNearBone(t.mesh.rest, open, surface, bone.bondDistance);
    say(t, o,
        c.summary(bone.name) + " (derived from the surface; " + std::to_string(candidates.size() - open.size()) +
            " candidates left to other bones' node sets)");
    if (c.empty()) throw SceneError(spec.file + ": " + field + ": " + c.summary(bone.name));
    std::vector<int>& nodes = t.boneNodes[b];
    for (int i : c.nodes)
      if (claimedBy[i] < 0) nodes.push_back(i);
  }
  if (!spec.skin.empty()) t.skin = readSurface(spec, spec.skin, "tissue.skin", SurfaceRequirement::OpenAllowed, t, o);
  t.quality = measureQuality(t.mesh);
  say(t, o, "tissue: " + qualityLine(t.quality));
  return t;
}

// The case's surfaces meshed into tetrahedra at `resolution` (TetGen), each bone's bonded nodes found.
CaseTissue meshCaseTissue(const CaseSpec& spec, Resolution resolution, const CaseTissueOptions& o) {
  CaseTissue t;
  SurfaceTissueInput in;
  in.envelope = readSurface(spec, spec.skin, "tissue.skin", SurfaceRole::Skin, t, o);
  for (size_t k = 0; k < spec.cavities.size(); ++k) {
    in.solids.push_back(readSurface(spec, spec.cavities[k], "tissue.cavities[" + std::to_string(k) + "]",
                                    SurfaceRequirement::Closed, t, o));
    in.names.push_back(fs::path(spec.cavities[k]).stem().string());
  }
  for (size_t b = 0; b < spec.bones.size(); ++b) {
    in.solids.push_back(
        readSurface(spec, spec.bones[b].surface, "bones[" + std::to_string(b) + "].surface", SurfaceRole::Bone, t, o));
    in.names.push_back(spec.bones[b].name);
    in.bones.push_back(static_cast<int>(in.solids.size()) - 1);
  }
  in.skinTriangles = spec.meshing.skinTriangles(resolution);
  in.maxRadiusEdgeRatio = spec.meshing.maxRadiusEdgeRatio;
  for (const CaseRefine& r : spec.meshing.refine) in.refine.push_back({r.center, r.radius, r.density});
  try {
    SurfaceTissue st = meshSurfaceTissue(in);
    t.mesh = std::move(st.mesh);
    t.skin = std::move(st.skin);
    t.skinNodes = std::move(st.skinNodes);
    t.skinTriangles = st.skinTriangles;
    const size_t firstBone = spec.cavities.size();
    for (size_t b = 0; b < spec.bones.size(); ++b) {
      t.boneNodes.push_back(st.solidNodes[firstBone + b]);
      if (t.boneNodes.back().empty())
        throw SceneError(spec.file + ": bones[" + std::to_string(b) + "] (" + spec.bones[b].name +
                         "): no tissue touches this bone, so nothing is bonded to it");
    }
    for (auto& line : st.report) say(t, o, line);
  } catch (const SceneError&) {
    throw;
  } catch (const std::exception& e) {
    throw SceneError(spec.file + ": meshing the tissue (" + resolutionName(resolution) + "): " + e.what());
  }
  t.quality = measureQuality(t.mesh);
  say(t, o, std::string("tissue (") + resolutionName(resolution) + "): " + qualityLine(t.quality));
  for (size_t b = 0; b < spec.bones.size(); ++b)
    say(t, o, spec.bones[b].name + ": " + std::to_string(t.boneNodes[b].size()) + " bonded nodes on its interface");
  return t;
}

// The tissue cached under `cachePath`, or nothing (a miss, a damaged or older entry).
std::optional<CaseTissue> readCached(const std::string& cachePath, Resolution resolution, const CaseTissueOptions& o,
                                     Clock::time_point t0) {
  std::optional<CaseTissue> cached = readTissueCache(cachePath);
  if (!cached) return std::nullopt;
  cached->fromCache = true;
  cached->seconds = since(t0);
  say(*cached, o, std::string("tissue: ") + resolutionName(resolution) + " model read from the cache " + cachePath);
  return cached;
}

}  // namespace

std::string defaultCacheDir() {
  if (const char* d = std::getenv("ORTHOSIM_CACHE"); d && *d) return d;
  if (const char* d = std::getenv("XDG_CACHE_HOME"); d && *d) return (fs::path(d) / "orthosim").string();
  if (const char* d = std::getenv("HOME"); d && *d) return (fs::path(d) / ".cache" / "orthosim").string();
  return (fs::temp_directory_path() / "orthosim-cache").string();
}

std::string caseTissueKey(const CaseSpec& spec, Resolution resolution) {
  Hash h;
  h.text(kSurfaceTissueVersion);
  h.text(resolutionName(resolution));
  h.number(spec.meshing.skinTriangles(resolution));
  h.number(spec.meshing.maxRadiusEdgeRatio);
  for (const CaseRefine& r : spec.meshing.refine) {
    for (int i = 0; i < 3; ++i) h.number(r.center[i]);
    h.number(r.radius);
    h.number(r.density);
  }
  h.file(spec.skin, "tissue.skin");
  for (const auto& c : spec.cavities) h.file(c, "tissue.cavities");
  for (const CaseBone& b : spec.bones) h.file(b.surface, "bones." + b.name);
  std::ostringstream s;
  s << std::hex << std::setw(16) << std::setfill('0') << h.h;
  return s.str();
}

CaseTissue buildCaseTissue(const CaseSpec& spec, Resolution resolution, const CaseTissueOptions& o) {
  const auto t0 = Clock::now();
  if (spec.isVolume()) {
    CaseTissue t = volumeTissue(spec, o);
    t.seconds = since(t0);
    return t;
  }
  if (o.cacheDir.empty()) {
    CaseTissue t = meshCaseTissue(spec, resolution, o);
    t.seconds = since(t0);
    return t;
  }
  const std::string cachePath = (fs::path(o.cacheDir) / (caseTissueKey(spec, resolution) + ".tissue")).string();
  if (std::optional<CaseTissue> cached = readCached(cachePath, resolution, o, t0)) return std::move(*cached);
  // One meshing per key: a thread or process (a worker beside another) that finds the same tissue
  // being meshed waits for it and reads the result, instead of meshing the same surfaces beside it.
  std::optional<FileLock> meshing;
  std::string unlocked;
  try {
    meshing.emplace(cachePath + ".lock");
  } catch (const FileLockError& e) {
    unlocked = e.what();
  }
  if (meshing)
    if (std::optional<CaseTissue> cached = readCached(cachePath, resolution, o, t0)) return std::move(*cached);
  CaseTissue t = meshCaseTissue(spec, resolution, o);
  if (!unlocked.empty()) say(t, o, "warning: meshed without the cache's lock: " + unlocked);
  t.seconds = since(t0);
  try {
    writeTissueCache(cachePath, t);
  } catch (const std::exception& e) {
    say(t, o, std::string("warning: tissue cache not written: ") + e.what());
  }
  return t;
}

}  // namespace orthosim
