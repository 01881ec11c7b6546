#include "session/ExportStore.hpp"

namespace orthosim::server {

ExportStore::ExportStore(std::size_t maxFilesPerOwner, std::size_t maxBytes)
    : maxFiles_(maxFilesPerOwner), maxBytes_(maxBytes) {}

std::string ExportStore::add(const std::string& owner, std::string fileName, std::string contentType,
                             std::string bytes) {
  ExportedFile f{randomHexId(), std::move(fileName), std::move(contentType), std::move(bytes)};
  const std::string id = f.id;
  const std::lock_guard<std::mutex> lock(mutex_);
  Owned& owned = owners_[owner];
  owned.bytes += f.bytes.size();
  bytes_ += f.bytes.size();
  owned.files.push_back(std::move(f));
  while (owned.files.size() > maxFiles_) dropOldest(owned);
  evictOverBytes(id);
  return id;
}

void ExportStore::dropOldest(Owned& owned) {
  owned.bytes -= owned.files.front().bytes.size();
  bytes_ -= owned.files.front().bytes.size();
  owned.files.pop_front();
}

// The file just added is kept even when it alone is over the bound: its link is being sent.
void ExportStore::evictOverBytes(const std::string& keepId) {
  while (bytes_ > maxBytes_) {
    auto largest = owners_.end();
    for (auto it = owners_.begin(); it != owners_.end(); ++it) {
      const bool onlyTheNewFile = it->second.files.size() == 1 && it->second.files.front().id == keepId;
      if (!it->second.files.empty() && !onlyTheNewFile &&
          (largest == owners_.end() || it->second.bytes > largest->second.bytes))
        largest = it;
    }
    if (largest == owners_.end()) return;
    dropOldest(largest->second);
    if (largest->second.files.empty()) owners_.erase(largest);
  }
}

std::optional<ExportedFile> ExportStore::find(const std::string& id) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  for (const auto& [owner, owned] : owners_)
    for (const ExportedFile& f : owned.files)
      if (f.id == id) return f;
  return std::nullopt;
}

void ExportStore::dropOwner(const std::string& owner) {
  const std::lock_guard<std::mutex> lock(mutex_);
  auto it = owners_.find(owner);
  if (it == owners_.end()) return;
  bytes_ -= it->second.bytes;
  owners_.erase(it);
}

std::size_t ExportStore::bytes() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return bytes_;
}

}  // namespace orthosim::server
