#pragma once
// What a job on the Redis queue is: a fine solve of a plan, a prediction band (`band` on a
// session), or one run of a cohort patient (`bench cohort --redis`). Code decides by the kind;
// the word is what travels in job messages and replies ("kind": "fine", "band", "cohort").
#include <optional>
#include <string_view>

namespace orthosim::server {

enum class JobKind { fine, band, cohort };

// "fine", "band" or "cohort".
const char* jobKindWord(JobKind kind);
// Nullopt for a word that names no kind.
std::optional<JobKind> jobKindOfWord(std::string_view word);

}  // namespace orthosim::server
