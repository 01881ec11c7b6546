#include "net/UploadSlots.hpp"

namespace orthosim::net {

std::shared_ptr<const void> UploadSlots::tryTake() {
  int now = taken_.load();
  do {
    if (now >= most_) return nullptr;
  } while (!taken_.compare_exchange_weak(now, now + 1));
  // An import may end after the server dropped its slots: the slot keeps them.
  return std::shared_ptr<const void>(this, [self = shared_from_this()](UploadSlots*) { --self->taken_; });
}

}  // namespace orthosim::net
