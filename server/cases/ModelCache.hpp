#pragma once
// The built models of the cases (a CaseModel per resolution, the coarse prototype Model), kept
// within a memory budget. A model nobody else holds is evicted, least recently used first, when
// the models kept add up to more than the budget; one a session or a job holds is never evicted,
// so asking for it again gives that same object, never a second copy. Each key is built once
// while other callers wait for it; a failed build is not kept. Sizes are estimates
// (cases/ModelSize.hpp) given with each build.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace orthosim::server {

// What `serve --model-memory` and `worker --model-memory` default to: room for a couple of dozen
// coarse cases (CaseModel and prototype) and fine ones beside them, below the memory of a machine
// that runs a few sessions at once; the estimate leaves out what allocators add, so the resident
// memory they take is higher.
inline constexpr std::size_t kDefaultModelMemoryMiB = 2048;

enum class ModelPart { Coarse, Fine, Prototype };

struct ModelKey {
  std::string caseId;
  ModelPart part = ModelPart::Coarse;
  bool operator<(const ModelKey& o) const { return std::tie(caseId, part) < std::tie(o.caseId, o.part); }
};

class ModelCache {
 public:
  using Built = std::pair<std::shared_ptr<const void>, std::size_t>;  // the model, its estimated bytes

  explicit ModelCache(std::size_t budgetBytes) : budget_(budgetBytes) {}

  // The model of `key`: kept, or made by `build` (returning it and its estimated bytes) once while
  // other callers wait; then unused models are evicted down to the budget. Throws what build throws.
  template <class T, class Build>
  std::shared_ptr<const T> get(const ModelKey& key, const Build& build) {
    return std::static_pointer_cast<const T>(obtain(key, [&]() -> Built { return build(); }));
  }
  // Drops the models of a case (its file changed): holders keep theirs, the next get() builds anew.
  void forget(const std::string& caseId);
  // Whether the model of `key` is built and kept now.
  bool resident(const ModelKey& key) const;
  // Estimated bytes of the models kept now (those in use included).
  std::size_t residentBytes() const;
  std::size_t budget() const { return budget_; }

 private:
  struct Entry {
    std::uint64_t serial = 0;                                  // which build: a forgotten key's next one differs
    std::shared_future<std::shared_ptr<const void>> building;  // valid while being built
    std::shared_ptr<const void> model;                         // null while being built
    std::size_t bytes = 0;
    std::uint64_t lastUse = 0;
  };

  std::shared_ptr<const void> obtain(const ModelKey& key, const std::function<Built()>& build);
  std::shared_ptr<const void> make(const ModelKey& key, const std::function<Built()>& build,
                                   std::unique_lock<std::mutex>& lock);
  // Under the lock: the least recently used of the models only this cache holds go until the kept
  // ones fit the budget (or only models in use are left). Returns them, to be freed after the lock.
  std::vector<std::shared_ptr<const void>> evictUnused();

  const std::size_t budget_;
  mutable std::mutex mutex_;
  std::map<ModelKey, Entry> entries_;
  std::uint64_t clock_ = 0;   // use order
  std::uint64_t serial_ = 0;  // builds
};

}  // namespace orthosim::server
