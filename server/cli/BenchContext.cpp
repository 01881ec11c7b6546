#include "cli/BenchContext.hpp"

#include <algorithm>
#include <ctime>
#include <fstream>
#include <stdexcept>

namespace orthosim::cli {

std::string loadAverage() {
  std::ifstream in("/proc/loadavg");
  std::string oneMinute;
  return in >> oneMinute ? oneMinute : std::string("unknown");
}

std::string utcNow() {
  const std::time_t t = std::time(nullptr);
  char s[32];
  std::strftime(s, sizeof s, "%Y-%m-%d %H:%M UTC", std::gmtime(&t));
  return s;
}

std::vector<CohortPatient> selectPatients(int count, const std::vector<std::string>& ids) {
  const std::vector<CohortPatient>& all = cohortPatients();
  if (ids.empty()) return {all.begin(), all.begin() + (count < 0 ? all.size() : std::min<size_t>(count, all.size()))};
  std::string known;
  for (const CohortPatient& p : all) known += (known.empty() ? "" : ", ") + p.id;
  for (const std::string& id : ids)
    if (std::none_of(all.begin(), all.end(), [&](const CohortPatient& p) { return p.id == id; }))
      throw std::invalid_argument("--patient: no patient '" + id + "' in the cohort (" + known + ")");
  std::vector<CohortPatient> out;
  for (const CohortPatient& p : all)
    if (std::find(ids.begin(), ids.end(), p.id) != ids.end()) out.push_back(p);
  return out;
}

}  // namespace orthosim::cli
