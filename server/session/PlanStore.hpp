#pragma once
// Saved plans on disk: DATA/plans/<case id>/<plan name>.json. Names are identifiers (checked
// here again), so a client's string never becomes an arbitrary path. A save writes a temporary
// file, flushes it to disk and renames it over the old one, so a crash or SIGTERM leaves either
// the old plan or the new one, never a torn file. A name already saved is replaced only when the
// caller says so: no session overwrites another's plan unasked.
#include <filesystem>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "session/PlanStamp.hpp"

namespace orthosim::server {

// A saved plan as list_plans names it.
struct PlanEntry {
  std::string name;
  PlanStamp stamp;
};

class PlanStore {
 public:
  explicit PlanStore(std::filesystem::path root);

  // Throws ProtocolError (bad_name) for a name that is not an identifier, ProtocolError
  // (plan_exists, naming who saved it and when) when the name is saved already and `replace` is
  // false, std::runtime_error when the file cannot be written.
  void save(const std::string& caseId, const std::string& name, const nlohmann::json& plan, bool replace = false);
  // Throws ProtocolError: bad_name, not_found, or bad_plan (unreadable JSON, naming the file).
  nlohmann::json load(const std::string& caseId, const std::string& name) const;
  // Names of the case's saved plans, sorted.
  std::vector<std::string> list(const std::string& caseId) const;
  // The same plans with who saved each and when (planStampOf; a file that cannot be read has an
  // empty stamp).
  std::vector<PlanEntry> entries(const std::string& caseId) const;

 private:
  std::filesystem::path file(const std::string& caseId, const std::string& name) const;
  PlanStamp stampOf(const std::filesystem::path& path) const;

  std::filesystem::path root_;
  std::mutex mutex_;  // two sessions saving the same name: one wins whole
};

}  // namespace orthosim::server
