#include "jobs/CohortResultFile.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include "eval/Statistics.hpp"
#include "jobs/ArrayJson.hpp"
#include "system/AtomicFile.hpp"

namespace orthosim::server {
using nlohmann::json;

std::string cohortResultFileName(const std::string& job) { return "jobs/" + job + ".cohort.json"; }

void writeCohortResult(const std::filesystem::path& file, const CohortOutcome& o) {
  const CohortRun& r = o.run;
  const json j = {{"format", kCohortResultFormat},
                  {"label", r.config.label},
                  {"requested_skin_triangles", r.config.skinTriangles},
                  {"tolerance_scale", r.config.toleranceScale},
                  {"max_total_iterations", r.config.maxTotalIterations},
                  {"skin_triangles", r.skinTriangles},
                  {"tets", r.tets},
                  {"nodes", r.nodes},
                  {"build_s", r.buildSeconds},
                  {"solve_times_s", r.solveTimes},
                  {"iterations", r.iterations},
                  {"chord_iterations", r.chordIterations},
                  {"warnings", r.warnings},
                  {"note", o.note},
                  {"rest", surfaceJson(r.rest)},
                  {"skin", surfaceJson(r.skin)}};
  std::filesystem::create_directories(file.parent_path());
  writeFileAtomically(file, j.dump());
}

CohortOutcome readCohortResult(const std::filesystem::path& file, const CaseSpec& spec) {
  const std::string name = file.string();
  const json j = readResultJson(file, "the cohort job's result", kCohortResultFormat);
  try {
    const auto integer = [&](const char* key) {
      const json& v = member(j, key, "");
      if (!v.is_number_integer() || v.get<long long>() < 0)
        throw BadResultFile(std::string("/") + key + ": must be a non-negative integer");
      return static_cast<int>(v.get<long long>());
    };
    const auto string = [&](const char* key) {
      const json& v = member(j, key, "");
      if (!v.is_string()) throw BadResultFile(std::string("/") + key + ": must be a string");
      return v.get<std::string>();
    };
    CohortOutcome o;
    CohortRun& r = o.run;
    r.config.label = string("label");
    r.config.skinTriangles = integer("requested_skin_triangles");
    r.config.maxTotalIterations = integer("max_total_iterations");
    const Eigen::VectorXd tol = readVector(json::array({member(j, "tolerance_scale", "")}), "/tolerance_scale");
    r.config.toleranceScale = tol[0];
    r.skinTriangles = integer("skin_triangles");
    r.tets = integer("tets");
    r.nodes = integer("nodes");
    r.iterations = integer("iterations");
    r.chordIterations = integer("chord_iterations");
    r.buildSeconds = readVector(json::array({member(j, "build_s", "")}), "/build_s")[0];
    const Eigen::VectorXd times = readVector(member(j, "solve_times_s", ""), "/solve_times_s");
    if (times.size() == 0) throw BadResultFile("/solve_times_s: must hold at least one time");
    r.solveTimes.assign(times.data(), times.data() + times.size());
    r.solveSeconds = median(r.solveTimes);
    const json& warnings = member(j, "warnings", "");
    if (!warnings.is_array()) throw BadResultFile("/warnings: must be an array of strings");
    for (size_t i = 0; i < warnings.size(); ++i) {
      if (!warnings[i].is_string()) throw BadResultFile("/warnings/" + std::to_string(i) + ": must be a string");
      r.warnings.push_back(warnings[i].get<std::string>());
    }
    o.note = string("note");
    r.rest = readSurface(member(j, "rest", ""), "/rest");
    r.skin = readSurface(member(j, "skin", ""), "/skin");
    if (r.rest.numVertices() != r.skin.numVertices() || r.rest.triangles.cols() != r.skin.triangles.cols() ||
        r.rest.triangles != r.skin.triangles)
      throw BadResultFile("/skin: not the rest skin deformed (other vertices or triangles than /rest)");
    r.spec = spec;
    r.spec.meshing.coarseSkinTriangles = r.config.skinTriangles;
    return o;
  } catch (const BadResultFile& e) {
    throw BadResultFile(name + ": " + e.what());
  }
}

}  // namespace orthosim::server
