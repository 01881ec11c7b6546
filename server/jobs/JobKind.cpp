#include "jobs/JobKind.hpp"

namespace orthosim::server {

const char* jobKindWord(JobKind kind) {
  switch (kind) {
    case JobKind::band:
      return "band";
    case JobKind::cohort:
      return "cohort";
    case JobKind::fine:
      break;
  }
  return "fine";
}

std::optional<JobKind> jobKindOfWord(std::string_view word) {
  for (JobKind kind : {JobKind::fine, JobKind::band, JobKind::cohort})
    if (word == jobKindWord(kind)) return kind;
  return std::nullopt;
}

}  // namespace orthosim::server
