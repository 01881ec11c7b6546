#pragma once
// The cases the server has opened, built once per (case, resolution) and shared by every session:
// a built CaseModel is immutable, each session solves on its own Model of it, made from one coarse
// prototype per case whose immutable parts it shares. Phantom cases are
// written under the data folder the first time they are asked for; tissue meshes are cached there.
// Built models are kept within a memory budget (cases/ModelCache): one no session or job holds is
// evicted, least recently used first, and built again (its mesh read from the cache) when asked for.
// Several processes may share the data folder (server replicas with --redis, workers): cases
// another one adds are found there (discoverWith), and a case whose file another one changed (an
// edit) is built again: a model is kept only while its case file is the one it was built from.
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "cases/CaseCatalog.hpp"
#include "cases/ModelCache.hpp"
#include "scene/CaseModel.hpp"
#include "solver/Model.hpp"

namespace orthosim::server {

class CaseLibrary {
 public:
  // modelBudgetBytes: the estimated bytes of built models kept (cases/ModelCache).
  CaseLibrary(std::vector<CaseEntry> catalog, std::filesystem::path dataDir,
              std::size_t modelBudgetBytes = kDefaultModelMemoryMiB << 20);

  // The cases now: the catalog grows while the server runs (patients imported from the page).
  std::vector<CaseEntry> catalog() const;
  std::optional<CaseEntry> find(const std::string& id) const;
  // Adds a case; throws std::invalid_argument when its id is taken.
  void add(CaseEntry entry);
  // Where cases added by other processes sharing the data folder are found (patients imported
  // through another replica): asked by catalog(), and by find() for an id it does not know, with
  // a test of the ids known already (to leave out); what it returns joins the catalog.
  using Discover = std::function<std::vector<CaseEntry>(const std::function<bool(const std::string&)>& known)>;
  void discoverWith(Discover discover);
  // Forgets the built models of a case whose file changed (an edit): the next model() builds it
  // again. Sessions holding the old models keep them until they let go. A case whose file was
  // replaced by another process is forgotten the same way by model() itself.
  void invalidate(const std::string& id);

  // Blocks until the model is built (or built by another caller); a failed build is not kept,
  // so a later call tries again. Throws std::invalid_argument for an unknown id, otherwise what
  // building throws (SceneError naming the case file and the defect).
  std::shared_ptr<const CaseModel> model(const std::string& id, Resolution resolution);
  bool isBuilt(const std::string& id, Resolution resolution) const;
  // Whether the model is kept now (built and not evicted), and the estimated bytes of all kept.
  bool isResident(const std::string& id, ModelPart part) const;
  std::size_t residentBytes() const { return models_.residentBytes(); }
  // The case file as it is on disk now (written first for a built-in case), without building
  // anything: what a worker hashes to tell whether a job was planned on this case. Throws as
  // model() does.
  CaseSpec spec(const std::string& id);
  // The solver model of the coarse case, built once: sessions make theirs from it with
  // Model(prototype, Model::ShareImmutable{}) and share its scene, energy, couplings, scatter
  // pattern, rest factorisation and contact surfaces. Nobody solves with the prototype itself.
  std::shared_ptr<const Model> coarsePrototype(const std::string& id);

 private:
  std::string caseFile(const CaseEntry& entry);
  // Joins the discovered cases to the catalog.
  void discover() const;
  // Forgets the models of a case whose file (folder and imported cases) is not the one they were
  // built from (another replica edited it).
  void forgetIfReplaced(const CaseEntry& entry);
  std::string artisynthCaseFile(const CaseEntry& entry);
  ModelCache::Built build(const CaseEntry& entry, Resolution resolution);

  mutable std::mutex catalogMutex_;
  mutable std::vector<CaseEntry> catalog_;  // grows by discover() in catalog() and find()
  Discover discover_;
  std::filesystem::path dataDir_;
  mutable std::mutex mutex_;  // builtFrom_
  std::mutex writeMutex_;     // writing a built-in case's files
  ModelCache models_;
  std::map<std::string, std::string> builtFrom_;  // case id -> its case file's identity (fileIdentity())
};

}  // namespace orthosim::server
