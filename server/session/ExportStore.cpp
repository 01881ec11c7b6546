#include "session/ExportStore.hpp"

#include <random>

namespace orthosim::server {

std::string randomHexId() {
  static thread_local std::random_device device;
  std::string id;
  static const char* digits = "0123456789abcdef";
  for (int i = 0; i < 4; ++i) {
    const unsigned v = device();
    for (int k = 0; k < 8; ++k) id += digits[(v >> (4 * k)) & 0xf];
  }
  return id;
}

ExportStore::ExportStore(std::size_t maxFiles, std::size_t maxBytes) : maxFiles_(maxFiles), maxBytes_(maxBytes) {}

std::string ExportStore::add(std::string fileName, std::string contentType, std::string bytes) {
  ExportedFile f{randomHexId(), std::move(fileName), std::move(contentType), std::move(bytes)};
  const std::string id = f.id;
  const std::lock_guard<std::mutex> lock(mutex_);
  bytes_ += f.bytes.size();
  files_.push_back(std::move(f));
  while (files_.size() > 1 && (files_.size() > maxFiles_ || bytes_ > maxBytes_)) {
    bytes_ -= files_.front().bytes.size();
    files_.pop_front();
  }
  return id;
}

std::optional<ExportedFile> ExportStore::find(const std::string& id) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  for (const ExportedFile& f : files_)
    if (f.id == id) return f;
  return std::nullopt;
}

}  // namespace orthosim::server
