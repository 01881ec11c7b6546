#include "scene/SceneFields.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "math/Angles.hpp"

namespace orthosim {

using nlohmann::json;
namespace fs = std::filesystem;

json parseJsonFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path + ": cannot open scene file");
  std::ostringstream ss;
  ss << in.rdbuf();
  try {
    return json::parse(ss.str());
  } catch (const json::exception& e) {  // syntax errors, and numbers beyond double (1e999)
    throw SceneError(path + ": malformed JSON: " + e.what());
  }
}

std::string resolvePath(const std::string& base, const std::string& p) {
  const fs::path q(p);
  return (q.is_absolute() ? q : fs::path(base) / q).string();
}

void readMaterial(JsonReader r, double& youngsModulus, double& poissonRatio) {
  const std::string model = r.has("model") ? r.string("model") : "neo-hookean";
  if (model != "neo-hookean") r.fail("unsupported model '" + model + "' (supported: neo-hookean)", "model");
  youngsModulus = r.number("youngs_modulus_kpa", 100.0) / 1000.0;
  poissonRatio = r.number("poisson_ratio", 0.47);
  if (youngsModulus <= 0) r.fail("must be positive", "youngs_modulus_kpa");
  if (poissonRatio <= -1.0 || poissonRatio >= 0.5) r.fail("must lie in (-1, 0.5)", "poisson_ratio");
  r.rejectUnknown();
}

FragmentMotion readFragmentMotion(JsonReader r) {
  FragmentMotion fm;
  fm.translation = r.vector3("translation_mm", Eigen::Vector3d::Zero());
  fm.rotation = r.vector3("rotation_deg", Eigen::Vector3d::Zero()) * (kPi / 180.0);
  fm.center = r.vector3("center_mm", Eigen::Vector3d::Zero());
  r.rejectUnknown();
  return fm;
}

std::array<bool, 3> readComponents(JsonReader& r) {
  std::array<bool, 3> c{false, false, false};
  if (!r.has("components")) return {true, true, true};
  const std::string s = r.string("components");
  for (char ch : s) {
    if (ch < 'x' || ch > 'z') r.fail("must be letters from 'xyz', e.g. \"xz\"", "components");
    c[ch - 'x'] = true;
  }
  return c;
}

void readSolverSettings(JsonReader r, SolverSettings& s) {
  s.substeps = r.integer("substeps", 0, 0, 10000);
  s.maxIterations = r.integer("max_iterations", s.maxIterations, 1, 1000);
  s.maxRefinements = r.integer("max_refinements", s.maxRefinements, 0, 30);
  s.maxTotalIterations = r.integer("max_total_iterations", s.maxTotalIterations, 1, 100000);
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
    if (h == "auto")
      s.hessian = HessianMode::Auto;
    else if (h == "projected")
      s.hessian = HessianMode::Projected;
    else if (h == "exact")
      s.hessian = HessianMode::Exact;
    else
      r.fail("must be \"auto\", \"projected\" or \"exact\"", "hessian");
  }
  r.rejectUnknown();
}

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

}  // namespace orthosim
