#include "cases/ModelCache.hpp"

#include <exception>
#include <iterator>

namespace orthosim::server {

std::shared_ptr<const void> ModelCache::obtain(const ModelKey& key, const std::function<Built()>& build) {
  std::unique_lock<std::mutex> lock(mutex_);
  auto it = entries_.find(key);
  if (it == entries_.end()) return make(key, build, lock);
  Entry& e = it->second;
  if (!e.model) {  // being built by another caller
    const std::shared_future<std::shared_ptr<const void>> building = e.building;
    lock.unlock();
    return building.get();
  }
  std::shared_ptr<const void> model = e.model;  // held here: not evicted by the pass below
  e.lastUse = ++clock_;
  const std::vector<std::shared_ptr<const void>> evicted = evictUnused();
  lock.unlock();  // freed after: a large model takes a while
  return model;
}

std::shared_ptr<const void> ModelCache::make(const ModelKey& key, const std::function<Built()>& build,
                                             std::unique_lock<std::mutex>& lock) {
  std::promise<std::shared_ptr<const void>> promise;
  Entry& entry = entries_[key];
  entry.serial = ++serial_;
  entry.building = promise.get_future().share();
  const std::uint64_t serial = entry.serial;
  lock.unlock();
  Built made;
  try {
    made = build();
  } catch (...) {
    lock.lock();
    auto it = entries_.find(key);
    if (it != entries_.end() && it->second.serial == serial) entries_.erase(it);
    lock.unlock();
    promise.set_exception(std::current_exception());
    throw;
  }
  std::vector<std::shared_ptr<const void>> evicted;
  lock.lock();
  auto it = entries_.find(key);
  if (it != entries_.end() && it->second.serial == serial) {  // not forgotten meanwhile
    Entry& e = it->second;
    e.model = made.first;
    e.bytes = made.second;
    e.lastUse = ++clock_;
    e.building = {};
    evicted = evictUnused();
  }
  lock.unlock();
  promise.set_value(made.first);
  return made.first;
}

std::vector<std::shared_ptr<const void>> ModelCache::evictUnused() {
  std::vector<std::shared_ptr<const void>> evicted;
  std::size_t kept = 0;
  for (const auto& [key, e] : entries_) kept += e.model ? e.bytes : 0;
  while (kept > budget_) {
    auto oldest = entries_.end();
    for (auto it = entries_.begin(); it != entries_.end(); ++it) {
      const Entry& e = it->second;
      // Only this cache holds it: no other copy exists, and none can be made but under this lock.
      if (e.model && e.model.use_count() == 1 && (oldest == entries_.end() || e.lastUse < oldest->second.lastUse))
        oldest = it;
    }
    if (oldest == entries_.end()) break;
    kept -= oldest->second.bytes;
    evicted.push_back(std::move(oldest->second.model));
    entries_.erase(oldest);
  }
  return evicted;
}

void ModelCache::forget(const std::string& caseId) {
  const std::lock_guard<std::mutex> lock(mutex_);
  for (auto it = entries_.begin(); it != entries_.end();)
    it = it->first.caseId == caseId ? entries_.erase(it) : std::next(it);
}

bool ModelCache::resident(const ModelKey& key) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  auto it = entries_.find(key);
  return it != entries_.end() && it->second.model != nullptr;
}

std::size_t ModelCache::residentBytes() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  std::size_t kept = 0;
  for (const auto& [key, e] : entries_) kept += e.model ? e.bytes : 0;
  return kept;
}

}  // namespace orthosim::server
