#include "scene/SceneFile.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "io/SurfaceImport.hpp"
#include "io/TetgenIO.hpp"
#include "mesh/SurfaceCheck.hpp"
#include "scene/SceneFields.hpp"

namespace orthosim {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Blend weights: one line per node, "node name weight [name weight ...]".
std::vector<BlendedNode> readBlendFile(const std::string& path, const Scene& scene, const std::string& field) {
  std::ifstream in(path);
  if (!in) throw SceneError(path + ": cannot open file (" + field + ")");
  std::vector<BlendedNode> out;
  std::set<int> seen;
  std::string line;
  for (int lineNo = 1; std::getline(in, line); ++lineNo) {
    const auto where = [&] { return path + ":" + std::to_string(lineNo) + " (" + field + "): "; };
    if (const auto h = line.find('#'); h != std::string::npos) line.resize(h);
    std::istringstream ss(line);
    BlendedNode b;
    if (!(ss >> b.node)) {
      if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
      throw SceneError(where() + "expected 'node fragment weight ...'");
    }
    if (b.node < 0 || b.node >= scene.mesh.numNodes())
      throw SceneError(where() + "node index " + std::to_string(b.node) + " is outside 0.." +
                       std::to_string(scene.mesh.numNodes() - 1));
    if (!seen.insert(b.node).second) throw SceneError(where() + "node " + std::to_string(b.node) + " is listed twice");
    std::string name;
    double w;
    while (ss >> name) {
      if (!(ss >> w) || !std::isfinite(w)) throw SceneError(where() + "missing or bad weight after '" + name + "'");
      const auto f = scene.fragmentIndex(name);
      if (!f) throw SceneError(where() + "unknown fragment '" + name + "'");
      b.weights.push_back({*f, w});
    }
    if (b.weights.empty()) throw SceneError(where() + "node " + std::to_string(b.node) + " has no weights");
    out.push_back(std::move(b));
  }
  return out;
}

}  // namespace

Scene loadSceneFile(const std::string& path) {
  const std::string base = fs::absolute(fs::path(path)).parent_path().string();
  const json j = parseJsonFile(path);
  Scene scene;
  JsonReader root(path, j, "");
  // Unknown top-level fields first: a misspelt section must not surface as its consequences.
  for (const char* k : {"units", "tissue", "fragments", "fixed", "blended", "contact", "plan", "solver"}) root.has(k);
  root.rejectUnknown();
  if (root.has("units") && root.string("units") != "mm") root.fail("only \"mm\" is supported", "units");

  {
    JsonReader tissue = root.child("tissue");
    const std::string node = resolvePath(base, tissue.string("node"));
    const std::string ele = resolvePath(base, tissue.string("ele"));
    try {
      TetgenMesh m = readTetgen(node, ele);
      scene.mesh = std::move(m.mesh);
      scene.indexBase = m.indexBase;
      validateMesh(scene.mesh, ele, scene.indexBase);
    } catch (const SceneError&) {
      throw;
    } catch (const std::exception& e) {
      tissue.fail(e.what());
    }
    if (tissue.has("material")) readMaterial(tissue.child("material"), scene.youngsModulus, scene.poissonRatio);
    tissue.rejectUnknown();
  }
  const int n = scene.mesh.numNodes();

  if (root.has("fragments")) {
    const json& arr = root.get("fragments");
    if (!arr.is_array()) root.fail("must be an array", "fragments");
    for (size_t i = 0; i < arr.size(); ++i) {
      JsonReader fr(path, arr[i], "fragments[" + std::to_string(i) + "]");
      FragmentSpec f;
      f.name = fr.string("name");
      if (scene.fragmentIndex(f.name)) fr.fail("duplicate fragment name '" + f.name + "'", "name");
      if (fr.has("nodes")) f.nodes = readNodeSet(resolvePath(base, fr.string("nodes")), n, fr.sub("nodes"));
      f.free = fr.boolean("free", false);
      fr.rejectUnknown();
      scene.fragments.push_back(std::move(f));
    }
  }

  if (root.has("fixed")) {
    const json& fx = root.get("fixed");
    const bool many = fx.is_array();
    for (size_t i = 0; i < (many ? fx.size() : 1); ++i) {
      JsonReader r(path, many ? fx[i] : fx, many ? "fixed[" + std::to_string(i) + "]" : "fixed");
      FixedSpec spec;
      spec.nodes = readNodeSet(resolvePath(base, r.string("nodes")), n, r.sub("nodes"));
      spec.components = readComponents(r);
      spec.displacement = r.vector3("displacement_mm", Eigen::Vector3d::Zero());
      r.rejectUnknown();
      scene.fixed.push_back(std::move(spec));
    }
  }

  if (root.has("blended")) {
    JsonReader r = root.child("blended");
    scene.blended = readBlendFile(resolvePath(base, r.string("weights")), scene, r.sub("weights"));
    r.rejectUnknown();
  }

  if (root.has("contact")) {
    root.forEach("contact", [&](JsonReader r) {
      ContactSpec c;
      c.name = r.has("name") ? r.string("name") : r.path();
      c.nodes = readNodeSet(resolvePath(base, r.string("nodes")), n, r.sub("nodes"));
      const std::string file = resolvePath(base, r.string("surface"));
      try {
        c.surface = importSurface(file);
        checkSurface(c.surface, file, SurfaceRequirement::OpenAllowed);  // outward where closed
      } catch (const std::exception& e) {
        r.fail(e.what(), "surface");
      }
      if (r.has("fragment")) {
        c.fragment = r.string("fragment");
        if (!scene.fragmentIndex(c.fragment)) r.fail("unknown fragment '" + c.fragment + "'", "fragment");
      }
      c.stiffness = r.number("stiffness_n_per_mm", 0.0);
      if (r.has("stiffness_n_per_mm") && !(c.stiffness > 0 && std::isfinite(c.stiffness)))
        r.fail("must be a positive number of N/mm", "stiffness_n_per_mm");
      r.rejectUnknown();
      scene.contacts.push_back(std::move(c));
    });
  }

  if (root.has("plan")) {
    JsonReader plan = root.child("plan");
    for (const auto& [name, motion] : plan.raw().items()) {
      plan.has(name);
      if (!scene.fragmentIndex(name)) plan.fail("unknown fragment '" + name + "'", name);
      scene.plan[name] = readFragmentMotion(JsonReader(path, motion, plan.sub(name)));
    }
  }

  if (root.has("solver")) readSolverSettings(root.child("solver"), scene.solver);
  root.rejectUnknown();
  return scene;
}

}  // namespace orthosim
