#include "scene/SceneFile.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "mesh/TetgenIO.hpp"

namespace orthosim {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr double kPi = 3.14159265358979323846;

// Reads fields of one JSON object, naming `file: path.to.field` in every error and refusing
// fields it does not know (a typo must not be silently ignored).
class Reader {
 public:
  Reader(std::string file, const json& j, std::string path) : file_(std::move(file)), j_(j), path_(std::move(path)) {
    if (!j_.is_object()) fail("must be an object");
  }

  [[noreturn]] void fail(const std::string& what, const std::string& field = "") const {
    std::string where = path_.empty() ? field : (field.empty() ? path_ : path_ + "." + field);
    throw SceneError(file_ + ": " + (where.empty() ? "" : where + ": ") + what);
  }
  bool has(const std::string& k) { seen_.insert(k); return j_.contains(k); }
  const json& get(const std::string& k) {
    if (!has(k)) fail("missing field", k);
    return j_.at(k);
  }
  Reader child(const std::string& k) { return Reader(file_, get(k), sub(k)); }
  std::string sub(const std::string& k) const { return path_.empty() ? k : path_ + "." + k; }

  double number(const std::string& k) {
    const json& v = get(k);
    if (!v.is_number()) fail("must be a number", k);
    const double d = v.get<double>();
    if (!std::isfinite(d)) fail("must be finite", k);
    return d;
  }
  double number(const std::string& k, double dflt) { return has(k) ? number(k) : dflt; }
  int integer(const std::string& k, int dflt, int lo, int hi) {
    if (!has(k)) return dflt;
    const json& v = j_.at(k);
    if (!v.is_number_integer()) fail("must be an integer", k);
    const long long i = v.get<long long>();
    if (i < lo || i > hi) fail("must lie in " + std::to_string(lo) + ".." + std::to_string(hi), k);
    return static_cast<int>(i);
  }
  bool boolean(const std::string& k, bool dflt) {
    if (!has(k)) return dflt;
    if (!j_.at(k).is_boolean()) fail("must be true or false", k);
    return j_.at(k).get<bool>();
  }
  std::string string(const std::string& k) {
    const json& v = get(k);
    if (!v.is_string() || v.get<std::string>().empty()) fail("must be a non-empty string", k);
    return v.get<std::string>();
  }
  Eigen::Vector3d vector3(const std::string& k, const Eigen::Vector3d& dflt) {
    if (!has(k)) return dflt;
    const json& v = j_.at(k);
    if (!v.is_array() || v.size() != 3) fail("must be an array of 3 numbers", k);
    Eigen::Vector3d out;
    for (int i = 0; i < 3; ++i) {
      if (!v[i].is_number()) fail("must be an array of 3 numbers", k);
      out[i] = v[i].get<double>();
      if (!std::isfinite(out[i])) fail("component " + std::to_string(i) + " must be finite", k);
    }
    return out;
  }
  void rejectUnknown() const {
    for (const auto& [k, v] : j_.items())
      if (!seen_.count(k)) fail("unknown field '" + k + "'");
  }
  const json& raw() const { return j_; }
  const std::string& file() const { return file_; }

 private:
  std::string file_;
  const json& j_;
  std::string path_;
  std::set<std::string> seen_;
};

fs::path resolve(const fs::path& base, const std::string& p) {
  const fs::path q(p);
  return q.is_absolute() ? q : base / q;
}

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path + ": cannot open scene file");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void readMaterial(Reader r, Scene& scene) {
  const std::string model = r.has("model") ? r.string("model") : "neo-hookean";
  if (model != "neo-hookean") r.fail("unsupported model '" + model + "' (supported: neo-hookean)", "model");
  scene.youngsModulus = r.number("youngs_modulus_kpa", 100.0) / 1000.0;
  scene.poissonRatio = r.number("poisson_ratio", 0.47);
  if (scene.youngsModulus <= 0) r.fail("must be positive", "youngs_modulus_kpa");
  if (scene.poissonRatio <= -1.0 || scene.poissonRatio >= 0.5) r.fail("must lie in (-1, 0.5)", "poisson_ratio");
  r.rejectUnknown();
}

std::array<bool, 3> readComponents(Reader& r) {
  std::array<bool, 3> c{false, false, false};
  if (!r.has("components")) return {true, true, true};
  const std::string s = r.string("components");
  for (char ch : s) {
    if (ch < 'x' || ch > 'z') r.fail("must be letters from 'xyz', e.g. \"xz\"", "components");
    c[ch - 'x'] = true;
  }
  return c;
}

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
      throw SceneError(where() + "node index " + std::to_string(b.node) + " is outside 0.." + std::to_string(scene.mesh.numNodes() - 1));
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

void readSolver(Reader r, SolverSettings& s) {
  s.substeps = r.integer("substeps", 0, 0, 10000);
  s.maxIterations = r.integer("max_iterations", s.maxIterations, 1, 1000);
  s.maxRefinements = r.integer("max_refinements", s.maxRefinements, 0, 30);
  if (r.has("force_tolerance_n")) {
    s.forceTolerance = r.number("force_tolerance_n");
    if (s.forceTolerance <= 0) r.fail("must be positive", "force_tolerance_n");
  }
  if (r.has("step_tolerance_mm")) {
    s.stepTolerance = r.number("step_tolerance_mm");
    if (s.stepTolerance <= 0) r.fail("must be positive", "step_tolerance_mm");
  }
  if (r.has("hessian")) {
    const std::string h = r.string("hessian");
    if (h == "auto") s.hessian = HessianMode::Auto;
    else if (h == "projected") s.hessian = HessianMode::Projected;
    else if (h == "exact") s.hessian = HessianMode::Exact;
    else r.fail("must be \"auto\", \"projected\" or \"exact\"", "hessian");
  }
  r.rejectUnknown();
}

}  // namespace

std::vector<int> readNodeSet(const std::string& path, int numNodes, const std::string& field) {
  std::ifstream in(path);
  if (!in) throw SceneError(path + ": cannot open node set (" + field + ")");
  std::vector<int> nodes;
  std::string line;
  for (int lineNo = 1; std::getline(in, line); ++lineNo) {
    if (const auto h = line.find('#'); h != std::string::npos) line.resize(h);
    std::istringstream ss(line);
    std::string tok;
    while (ss >> tok) {
      char* end = nullptr;
      const long v = std::strtol(tok.c_str(), &end, 10);
      const std::string where = path + ":" + std::to_string(lineNo) + " (" + field + "): ";
      if (end == tok.c_str() || *end != '\0') throw SceneError(where + "'" + tok + "' is not a node index");
      if (v < 0 || v >= numNodes)
        throw SceneError(where + "node index " + tok + " is outside 0.." + std::to_string(numNodes - 1));
      nodes.push_back(static_cast<int>(v));
    }
  }
  return nodes;
}

Scene loadSceneFile(const std::string& path) {
  const fs::path base = fs::absolute(fs::path(path)).parent_path();
  json j;
  try {
    j = json::parse(readFile(path));
  } catch (const json::exception& e) {  // syntax errors, and numbers beyond double (1e999)
    throw SceneError(path + ": malformed JSON: " + e.what());
  }
  Scene scene;
  Reader root(path, j, "");
  // Unknown top-level fields first: a misspelt section must not surface as its consequences.
  for (const char* k : {"units", "tissue", "fragments", "fixed", "blended", "plan", "solver"}) root.has(k);
  root.rejectUnknown();
  if (root.has("units") && root.string("units") != "mm") root.fail("only \"mm\" is supported", "units");

  {
    Reader tissue = root.child("tissue");
    const std::string node = resolve(base, tissue.string("node")).string();
    const std::string ele = resolve(base, tissue.string("ele")).string();
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
    if (tissue.has("material")) readMaterial(tissue.child("material"), scene);
    tissue.rejectUnknown();
  }
  const int n = scene.mesh.numNodes();

  if (root.has("fragments")) {
    const json& arr = root.get("fragments");
    if (!arr.is_array()) root.fail("must be an array", "fragments");
    for (size_t i = 0; i < arr.size(); ++i) {
      Reader fr(path, arr[i], "fragments[" + std::to_string(i) + "]");
      FragmentSpec f;
      f.name = fr.string("name");
      if (scene.fragmentIndex(f.name)) fr.fail("duplicate fragment name '" + f.name + "'", "name");
      if (fr.has("nodes")) f.nodes = readNodeSet(resolve(base, fr.string("nodes")).string(), n, fr.sub("nodes"));
      f.free = fr.boolean("free", false);
      fr.rejectUnknown();
      scene.fragments.push_back(std::move(f));
    }
  }

  if (root.has("fixed")) {
    const json& fx = root.get("fixed");
    const bool many = fx.is_array();
    for (size_t i = 0; i < (many ? fx.size() : 1); ++i) {
      Reader r(path, many ? fx[i] : fx, many ? "fixed[" + std::to_string(i) + "]" : "fixed");
      FixedSpec spec;
      spec.nodes = readNodeSet(resolve(base, r.string("nodes")).string(), n, r.sub("nodes"));
      spec.components = readComponents(r);
      spec.displacement = r.vector3("displacement_mm", Eigen::Vector3d::Zero());
      r.rejectUnknown();
      scene.fixed.push_back(std::move(spec));
    }
  }

  if (root.has("blended")) {
    Reader r = root.child("blended");
    scene.blended = readBlendFile(resolve(base, r.string("weights")).string(), scene, r.sub("weights"));
    r.rejectUnknown();
  }

  if (root.has("plan")) {
    Reader plan = root.child("plan");
    for (const auto& [name, motion] : plan.raw().items()) {
      plan.has(name);
      if (!scene.fragmentIndex(name)) plan.fail("unknown fragment '" + name + "'", name);
      Reader m(path, motion, plan.sub(name));
      FragmentMotion fm;
      fm.translation = m.vector3("translation_mm", Eigen::Vector3d::Zero());
      fm.rotation = m.vector3("rotation_deg", Eigen::Vector3d::Zero()) * (kPi / 180.0);
      fm.center = m.vector3("center_mm", Eigen::Vector3d::Zero());
      m.rejectUnknown();
      scene.plan[name] = fm;
    }
  }

  if (root.has("solver")) readSolver(root.child("solver"), scene.solver);
  root.rejectUnknown();
  return scene;
}

}  // namespace orthosim
