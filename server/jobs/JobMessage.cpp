#include "jobs/JobMessage.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "cases/Identifier.hpp"
#include "system/AtomicFile.hpp"

namespace orthosim::server {
using nlohmann::json;
namespace {

constexpr const char* kStreamPrefix = "orthosim:";

json vec(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }

Eigen::Vector3d readVec(const json& j, const std::string& where) {
  if (!j.is_array() || j.size() != 3) throw BadJobMessage(where + ": must be an array of 3 numbers");
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) {
    if (!j[i].is_number()) throw BadJobMessage(where + "/" + std::to_string(i) + ": must be a number");
    v[i] = j[i].get<double>();
    if (!std::isfinite(v[i])) throw BadJobMessage(where + "/" + std::to_string(i) + ": must be finite");
  }
  return v;
}

std::string readString(const json& j, const char* key) {
  auto it = j.find(key);
  if (it == j.end()) throw BadJobMessage(std::string("/") + key + ": required field is missing");
  if (!it->is_string() || it->get<std::string>().empty())
    throw BadJobMessage(std::string("/") + key + ": must be a non-empty string");
  return it->get<std::string>();
}

bool isJobName(const std::string& s) {
  if (s.empty() || s.size() > 128) return false;
  for (char ch : s)
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '-' || ch == '_')) return false;
  return true;
}

struct Fnv64 {
  std::uint64_t h = 1469598103934665603ull;
  void bytes(const char* p, size_t n) {
    for (size_t i = 0; i < n; ++i) {
      h ^= static_cast<unsigned char>(p[i]);
      h *= 1099511628211ull;
    }
  }
  void text(const std::string& s) {
    const std::uint64_t n = s.size();
    bytes(reinterpret_cast<const char*>(&n), sizeof n);
    bytes(s.data(), s.size());
  }
  void file(const std::string& path, const std::string& role) {
    text(role);
    if (path.empty()) return text("(none)");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("cannot read " + path + " (" + role + ") to hash the case");
    std::ostringstream s;
    s << in.rdbuf();
    text(s.str());
  }
};

}  // namespace

std::string replyStreamName(const std::string& serverId) { return std::string(kStreamPrefix) + "replies:" + serverId; }
std::string cancelKey(const std::string& job) { return std::string(kStreamPrefix) + "cancel:" + job; }

std::string encodeJobMessage(const JobMessage& job) {
  json plan = json::object();
  for (const auto& [name, m] : job.plan)
    plan[name] = {
        {"translation_mm", vec(m.translation)}, {"rotation_rad", vec(m.rotation)}, {"center_mm", vec(m.center)}};
  json j{{"format", kJobFormat},
         {"job", job.job},
         {"kind", jobKindWord(job.kind)},
         {"case", job.caseId},
         {"case_hash", job.caseHash},
         {"resolution", resolutionName(job.resolution)},
         {"reply_stream", job.replyStream},
         {"plan", plan}};
  if (job.band) j["band"] = bandJobSpecJson(*job.band);
  if (job.cohort) j["cohort"] = cohortJobSpecJson(*job.cohort);
  return j.dump();
}

JobMessage decodeJobMessage(const std::string& text) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::parse_error& e) {
    throw BadJobMessage(std::string("not JSON: ") + e.what());
  }
  if (!j.is_object()) throw BadJobMessage("/: must be a JSON object");
  const std::string format = readString(j, "format");
  if (format != kJobFormat)
    throw BadJobMessage("/format: '" + format + "' is not " + kJobFormat + " (a job of another deployment or version)");
  for (const auto& [key, value] : j.items()) {
    static const char* known[] = {"format",     "job",          "kind", "case", "case_hash",
                                  "resolution", "reply_stream", "plan", "band", "cohort"};
    if (std::find(std::begin(known), std::end(known), key) == std::end(known))
      throw BadJobMessage("/" + key + ": unknown field");
  }
  JobMessage m;
  m.job = readString(j, "job");
  if (!isJobName(m.job)) throw BadJobMessage("/job: '" + m.job + "' is not a job name (letters, digits, - and _)");
  const std::string kind = readString(j, "kind");
  const std::optional<JobKind> known = jobKindOfWord(kind);
  if (!known) throw BadJobMessage("/kind: '" + kind + "' is not a job kind this worker runs (fine, band, cohort)");
  m.kind = *known;
  const bool band = m.kind == JobKind::band, cohort = m.kind == JobKind::cohort;
  if (j.contains("band") != band)
    throw BadJobMessage(band ? "/band: required field is missing" : "/band: only a band job has band options");
  if (j.contains("cohort") != cohort)
    throw BadJobMessage(cohort ? "/cohort: required field is missing"
                               : "/cohort: only a cohort job has cohort options");
  if (band) m.band = readBandJobSpec(j["band"], "/band");
  if (cohort) m.cohort = readCohortJobSpec(j["cohort"], "/cohort");
  m.caseId = readString(j, "case");
  if (!isIdentifier(m.caseId)) throw BadJobMessage("/case: '" + m.caseId + "' is not a case identifier");
  m.caseHash = readString(j, "case_hash");
  if (m.caseHash.size() != 16 || m.caseHash.find_first_not_of("0123456789abcdef") != std::string::npos)
    throw BadJobMessage("/case_hash: must be 16 lower-case hex digits");
  const std::string resolution = readString(j, "resolution");
  if (resolution == "fine")
    m.resolution = Resolution::Fine;
  else if (resolution == "coarse")
    m.resolution = Resolution::Coarse;
  else
    throw BadJobMessage("/resolution: '" + resolution + "' is not one of coarse, fine");
  m.replyStream = readString(j, "reply_stream");
  if (m.replyStream.rfind(std::string(kStreamPrefix) + "replies:", 0) != 0 ||
      !isJobName(m.replyStream.substr(std::string(kStreamPrefix).size() + 8)))
    throw BadJobMessage("/reply_stream: '" + m.replyStream + "' is not an orthosim reply stream");
  auto plan = j.find("plan");
  if (plan == j.end()) throw BadJobMessage("/plan: required field is missing");
  if (!plan->is_object()) throw BadJobMessage("/plan: must be an object of fragment motions");
  for (const auto& [name, motion] : plan->items()) {
    const std::string where = "/plan/" + name;
    if (name.empty() || name.size() > 64) throw BadJobMessage(where + ": not a fragment name");
    if (!motion.is_object()) throw BadJobMessage(where + ": must be an object");
    for (const auto& [key, value] : motion.items())
      if (key != "translation_mm" && key != "rotation_rad" && key != "center_mm")
        throw BadJobMessage(where + "/" + key + ": unknown field");
    FragmentMotion f;
    for (const char* key : {"translation_mm", "rotation_rad", "center_mm"})
      if (!motion.contains(key)) throw BadJobMessage(where + "/" + key + ": required field is missing");
    f.translation = readVec(motion["translation_mm"], where + "/translation_mm");
    f.rotation = readVec(motion["rotation_rad"], where + "/rotation_rad");
    f.center = readVec(motion["center_mm"], where + "/center_mm");
    m.plan[name] = f;
  }
  if (m.kind == JobKind::cohort && !m.plan.empty())
    throw BadJobMessage("/plan: a cohort job's plan is its patient's (must be empty)");
  return m;
}

std::string caseContentHash(const CaseSpec& spec) {
  Fnv64 h;
  h.text(kJobFormat);
  h.file(spec.file, "case file");
  h.file(spec.skin, "tissue.skin");
  for (const std::string& c : spec.cavities) h.file(c, "tissue.cavities");
  for (const CaseBone& b : spec.bones) h.file(b.surface, "bones." + b.name);
  if (spec.isVolume()) {
    h.file(spec.node, "tissue.node");
    h.file(spec.ele, "tissue.ele");
  }
  std::ostringstream s;
  s << std::hex << std::setw(16) << std::setfill('0') << h.h;
  return s.str();
}

std::string resultFileName(const std::string& job) { return "jobs/" + job + ".nodes"; }

static constexpr char kNodesMagic[] = "orthosim-nodes-1\n";

void writeResultNodes(const std::filesystem::path& file, const Eigen::Matrix3Xd& x) {
  namespace fs = std::filesystem;
  fs::create_directories(file.parent_path());
  AtomicFile out(file, file.filename().string() + ".part-");  // removed when a write fails (a full disk)
  const std::uint64_t n = static_cast<std::uint64_t>(x.cols());
  out.out().write(kNodesMagic, sizeof kNodesMagic - 1);
  out.out().write(reinterpret_cast<const char*>(&n), sizeof n);
  out.out().write(reinterpret_cast<const char*>(x.data()), static_cast<std::streamsize>(sizeof(double) * x.size()));
  out.commit(Durability::Synced);
}

Eigen::Matrix3Xd readResultNodes(const std::filesystem::path& file, long long nodes) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error("the job's result " + file.string() + " cannot be read");
  char magic[sizeof kNodesMagic - 1];
  std::uint64_t n = 0;
  if (!in.read(magic, sizeof magic) || std::string(magic, sizeof magic) != std::string(kNodesMagic, sizeof magic))
    throw std::runtime_error(file.string() + " is not an orthosim node file");
  if (!in.read(reinterpret_cast<char*>(&n), sizeof n) || static_cast<long long>(n) != nodes)
    throw std::runtime_error(file.string() + " holds " + std::to_string(n) + " nodes, the fine model has " +
                             std::to_string(nodes));
  Eigen::Matrix3Xd x(3, static_cast<Eigen::Index>(n));
  if (!in.read(reinterpret_cast<char*>(x.data()), static_cast<std::streamsize>(sizeof(double) * x.size())))
    throw std::runtime_error(file.string() + " is shorter than its " + std::to_string(n) + " nodes");
  if (!x.allFinite()) throw std::runtime_error(file.string() + " holds a non-finite coordinate");
  return x;
}

}  // namespace orthosim::server
