#include "scene/CaseFile.hpp"

#include <cmath>
#include <filesystem>
#include <set>

#include "scene/PlanFile.hpp"
#include "scene/SceneFields.hpp"

namespace orthosim {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// name: [x, y, z], optionally grouped under "hard" and "soft"; a landmarks file may also say its
// "units" (mm) and describe itself ("variant", "description").
void readLandmarkObject(JsonReader r, Landmarks& out) {
  for (const auto& [name, value] : r.raw().items()) {
    if (name == "units") {
      if (r.string("units") != "mm") r.fail("only \"mm\" is supported", "units");
      continue;
    }
    if (name == "variant" || name == "description") {
      r.has(name);
      continue;
    }
    if (name == "hard" || name == "soft") {
      if (value.is_object()) {
        readLandmarkObject(r.child(name), out);
        continue;
      }
    }
    if (out.count(name)) r.fail("landmark '" + name + "' is given twice", name);
    out[name] = r.vector3(name);
  }
  r.rejectUnknown();
}

Eigen::Vector3d unitVector(JsonReader& r, const std::string& k, const Eigen::Vector3d& dflt) {
  const Eigen::Vector3d v = r.vector3(k, dflt);
  if (std::abs(v.norm() - 1.0) > 1e-6) r.fail("must be a unit vector", k);
  return v;
}

void readFrame(JsonReader r, AnatomicalFrame& f) {
  f.anterior = unitVector(r, "anterior", f.anterior);
  f.superior = unitVector(r, "superior", f.superior);
  f.right = unitVector(r, "right", f.right);
  if (std::abs(f.anterior.dot(f.superior)) > 1e-6 || std::abs(f.anterior.dot(f.right)) > 1e-6 ||
      std::abs(f.superior.dot(f.right)) > 1e-6)
    r.fail("anterior, superior and right must be orthogonal");
  r.rejectUnknown();
}

void readTissue(JsonReader r, const std::string& base, CaseSpec& c) {
  if (r.has("skin")) c.skin = resolvePath(base, r.string("skin"));
  if (r.has("texture")) c.texture = resolvePath(base, r.string("texture"));
  if (r.has("node")) c.node = resolvePath(base, r.string("node"));
  if (r.has("ele")) c.ele = resolvePath(base, r.string("ele"));
  if (c.node.empty() != c.ele.empty()) r.fail("a tetrahedral tissue needs both 'node' and 'ele'");
  if (r.has("cavities")) {
    const json& arr = r.get("cavities");
    if (!arr.is_array()) r.fail("must be an array of file names", "cavities");
    for (const json& p : arr) {
      if (!p.is_string() || p.get<std::string>().empty()) r.fail("must be an array of file names", "cavities");
      c.cavities.push_back(resolvePath(base, p.get<std::string>()));
    }
  }
  if (c.node.empty() && c.skin.empty()) r.fail("needs a skin surface ('skin') or tetrahedra ('node' and 'ele')");
  if (!c.node.empty() && !c.cavities.empty())
    r.fail("cavities only apply to a skin envelope, not to given tetrahedra", "cavities");
  if (r.has("material")) readMaterial(r.child("material"), c.youngsModulus, c.poissonRatio);
  r.rejectUnknown();
}

CaseBone readBone(JsonReader r, const std::string& base, bool volume) {
  CaseBone b;
  b.name = r.string("name");
  b.fixed = r.boolean("fixed", false);
  if (r.has("nodes")) {
    if (!volume) r.fail("node sets apply to given tetrahedra; a surface case finds the bonded nodes itself", "nodes");
    b.nodes = resolvePath(base, r.string("nodes"));
  }
  b.derive = r.boolean("derive", b.nodes.empty());
  if (!volume && r.has("derive")) r.fail("applies to given tetrahedra only", "derive");
  if (b.derive || !volume || r.has("surface")) b.surface = resolvePath(base, r.string("surface"));
  if (r.has("candidates")) {
    if (!volume) r.fail("applies to given tetrahedra only", "candidates");
    b.candidates = resolvePath(base, r.string("candidates"));
  }
  b.bondDistance = r.number("bond_distance_mm", b.bondDistance);
  if (b.bondDistance <= 0 || b.bondDistance > 20) r.fail("must lie in (0, 20] mm", "bond_distance_mm");
  r.rejectUnknown();
  return b;
}

OsteotomySpec readCut(JsonReader r) {
  OsteotomySpec cut;
  cut.bone = r.string("bone");
  if (r.has("template")) {
    cut.kind = r.string("template");
    if (r.has("side")) cut.side = r.string("side");
    if (r.has("offset_mm")) {
      cut.offset = r.number("offset_mm");
      if (cut.offset < 0 || cut.offset > 50) r.fail("must lie in 0..50 mm", "offset_mm");
    }
    if (r.has("tilt_deg")) {
      cut.tilt = r.number("tilt_deg");
      if (!(std::abs(cut.tilt) <= 30)) r.fail("must lie in -30..30 degrees", "tilt_deg");
      if (cut.tilt != 0 && !osteotomyTilts(cut.kind))
        r.fail("only le_fort_1, segmented_maxilla and genioplasty cuts tilt", "tilt_deg");
    }
  } else {
    cut.kind = "planes";
    cut.fragment = r.string("fragment");
    r.forEach("planes", [&](JsonReader p) {
      CutPlane plane{p.vector3("point_mm"), p.vector3("normal")};
      if (plane.normal.norm() < 1e-9) p.fail("must not be zero", "normal");
      plane.normal.normalize();
      p.rejectUnknown();
      cut.planes.push_back(plane);
    });
  }
  r.rejectUnknown();
  return cut;
}

void readMeshing(JsonReader r, const Landmarks& landmarks, CaseMeshing& m) {
  m.coarseSkinTriangles = r.integer("coarse_skin_triangles", m.coarseSkinTriangles, 200, 2000000);
  m.fineSkinTriangles = r.integer("fine_skin_triangles", m.fineSkinTriangles, 200, 2000000);
  m.maxRadiusEdgeRatio = r.number("max_radius_edge_ratio", m.maxRadiusEdgeRatio);
  if (m.maxRadiusEdgeRatio != 0 && (m.maxRadiusEdgeRatio < 1.0 || m.maxRadiusEdgeRatio > 10))
    r.fail("must be 0 (no refinement) or lie in 1..10", "max_radius_edge_ratio");
  if (r.has("refine")) {
    m.refine.clear();
    r.forEach("refine", [&](JsonReader q) {
      CaseRefine f;
      if (q.has("landmark")) {
        f.landmark = q.string("landmark");
        const auto it = landmarks.find(f.landmark);
        if (it == landmarks.end()) q.fail("unknown landmark '" + f.landmark + "'", "landmark");
        f.center = it->second;
      } else {
        f.center = q.vector3("center_mm");
      }
      f.radius = q.number("radius_mm", f.radius);
      f.density = q.number("density", f.density);
      if (f.radius <= 0) q.fail("must be positive", "radius_mm");
      if (f.density < 0.1 || f.density > 20) q.fail("must lie in 0.1..20", "density");
      q.rejectUnknown();
      m.refine.push_back(f);
    });
  }
  r.rejectUnknown();
}

}  // namespace

const char* resolutionName(Resolution r) { return r == Resolution::Coarse ? "coarse" : "fine"; }

bool isCaseJson(const json& j) { return j.is_object() && j.contains("bones"); }

std::vector<std::string> CaseSpec::fragmentNames() const {
  std::vector<std::string> names;
  for (const CaseBone& b : bones) names.push_back(b.name);
  for (const FragmentRegion& r : regions) names.push_back(r.name);
  return names;
}

std::string CaseSpec::boneOf(const std::string& fragment) const {
  for (const CaseBone& b : bones)
    if (b.name == fragment) return b.name;
  for (const FragmentRegion& r : regions)
    if (r.name == fragment) return boneOf(r.parent);
  return {};
}

CaseSpec loadCaseFile(const std::string& path) {
  CaseSpec c;
  c.file = fs::absolute(fs::path(path)).string();
  const std::string base = fs::path(c.file).parent_path().string();
  const json j = parseJsonFile(path);
  JsonReader root(path, j, "");
  for (const char* k : {"units", "name", "frame", "tissue", "bones", "fixed", "landmarks", "cuts", "blend_width_mm",
                        "meshing", "contact", "plan", "solver"})
    root.has(k);
  root.rejectUnknown();
  if (root.has("units") && root.string("units") != "mm") root.fail("only \"mm\" is supported", "units");
  c.name = root.has("name") ? root.string("name") : fs::path(path).stem().string();
  if (root.has("frame")) readFrame(root.child("frame"), c.frame);
  readTissue(root.child("tissue"), base, c);

  std::set<std::string> names;
  root.forEach("bones", [&](JsonReader b) {
    c.bones.push_back(readBone(std::move(b), base, c.isVolume()));
    if (!names.insert(c.bones.back().name).second)
      root.fail("bone name '" + c.bones.back().name + "' is used twice", "bones");
  });
  if (c.bones.empty()) root.fail("must list at least one bone", "bones");
  if (root.has("fixed")) {
    if (!c.isVolume()) root.fail("node sets apply to given tetrahedra only; hold tissue with a fixed bone", "fixed");
    root.forEach("fixed", [&](JsonReader r) {
      CaseFixed f;
      f.nodes = resolvePath(base, r.string("nodes"));
      f.components = readComponents(r);
      r.rejectUnknown();
      c.fixed.push_back(f);
    });
  }

  if (root.has("landmarks")) {
    const json& lm = root.get("landmarks");
    if (lm.is_string()) {
      const std::string file = resolvePath(base, lm.get<std::string>());
      const json lj = parseJsonFile(file);
      readLandmarkObject(JsonReader(file, lj, ""), c.landmarks);
    } else {
      readLandmarkObject(root.child("landmarks"), c.landmarks);
    }
  }

  if (root.has("cuts")) {
    root.forEach("cuts", [&](JsonReader r) {
      const std::string where = r.path();
      OsteotomySpec cut = readCut(std::move(r));
      if (!names.count(cut.bone)) root.fail("'" + cut.bone + "' is no bone or earlier fragment", where + ".bone");
      try {
        for (FragmentRegion& region : osteotomyRegions(cut, c.landmarks, c.frame)) {
          if (!names.insert(region.name).second)
            root.fail("makes fragment '" + region.name + "', a name already in use", where);
          c.regions.push_back(std::move(region));
        }
      } catch (const std::invalid_argument& e) {
        root.fail(e.what(), where);
      }
      c.cuts.push_back(std::move(cut));
    });
  }
  c.blendWidth = root.number("blend_width_mm", c.blendWidth);
  if (c.blendWidth <= 0 || c.blendWidth > 50) root.fail("must lie in (0, 50] mm", "blend_width_mm");
  if (root.has("meshing")) {
    if (c.isVolume()) root.fail("applies to surface cases only (the tetrahedra are given)", "meshing");
    readMeshing(root.child("meshing"), c.landmarks, c.meshing);
  }

  if (root.has("contact")) {
    root.forEach("contact", [&](JsonReader r) {
      CaseContact contact;
      const json& bones = r.get("bones");
      if (!bones.is_array()) r.fail("must be an array of bone names", "bones");
      for (const json& b : bones) {
        bool known = false;
        for (const CaseBone& cb : c.bones) known = known || (b.is_string() && cb.name == b.get<std::string>());
        if (!known) r.fail(b.dump() + " is no bone of this case", "bones");
        contact.bones.push_back(b.get<std::string>());
      }
      if (contact.bones.empty()) r.fail("must list at least one bone", "bones");
      contact.rangeMm = r.number("range_mm", contact.rangeMm);
      if (!(contact.rangeMm > 0 && contact.rangeMm <= 100)) r.fail("must lie in (0, 100] mm", "range_mm");
      if (r.has("max_depth_mm")) {
        contact.maxDepthMm = r.number("max_depth_mm");
        if (!(contact.maxDepthMm > 0 && contact.maxDepthMm <= 200)) r.fail("must lie in (0, 200] mm", "max_depth_mm");
        if (c.skin.empty()) r.fail("needs the case's skin surface (tissue.skin) to measure depth from", "max_depth_mm");
      }
      if (r.has("stiffness_n_per_mm")) {
        contact.stiffness = r.number("stiffness_n_per_mm");
        if (!(contact.stiffness > 0 && std::isfinite(contact.stiffness)))
          r.fail("must be a positive number of N/mm", "stiffness_n_per_mm");
      }
      r.rejectUnknown();
      c.contacts.push_back(contact);
    });
  }

  if (root.has("plan")) c.plan = readCasePlan(root.child("plan"), c);
  if (root.has("solver")) readSolverSettings(root.child("solver"), c.solver);
  root.rejectUnknown();
  return c;
}

}  // namespace orthosim
