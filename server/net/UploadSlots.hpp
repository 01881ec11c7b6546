#pragma once
// How many uploads (POST /api/patients, POST /api/scans) may be under way at once, being received
// or imported: each holds a file of up to HttpLimits::uploadBytes on disk and its import's memory,
// so one more is refused at its headers (503 too_many_uploads) before its body is read.
#include <atomic>
#include <memory>

namespace orthosim::net {

class UploadSlots : public std::enable_shared_from_this<UploadSlots> {
 public:
  // Made with std::make_shared: a slot keeps its UploadSlots alive.
  explicit UploadSlots(int most) : most_(most) {}

  // A slot, given back when the last copy of the pointer goes; nullptr when `most` are taken.
  std::shared_ptr<const void> tryTake();
  int taken() const { return taken_.load(); }
  int most() const { return most_; }

 private:
  const int most_;
  std::atomic<int> taken_{0};
};

}  // namespace orthosim::net
