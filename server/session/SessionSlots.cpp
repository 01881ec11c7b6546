#include "session/SessionSlots.hpp"

#include <algorithm>

namespace orthosim::server {

SessionSlots::Slot::Slot(SessionSlots& slots, Clock::time_point since) : slots_(slots), since_(since), heard_(since) {}

SessionSlots::Slot::~Slot() {
  const std::lock_guard<std::mutex> lock(slots_.mutex_);
  if (held_) slots_.held_.remove(this);
}

void SessionSlots::Slot::whenNeeded(std::function<bool()> hasCase, std::function<void()> giveUp) {
  const std::lock_guard<std::mutex> lock(slots_.mutex_);
  hasCase_ = std::move(hasCase);
  giveUp_ = std::move(giveUp);
}

void SessionSlots::Slot::heard() {
  const std::lock_guard<std::mutex> lock(slots_.mutex_);
  heard_ = slots_.now_();
}

void SessionSlots::Slot::rejoin() {
  const std::lock_guard<std::mutex> lock(slots_.mutex_);
  if (held_) return;
  held_ = true;
  slots_.held_.push_back(this);
}

SessionSlots::SessionSlots(int maxSessions, std::chrono::milliseconds grace, std::function<Clock::time_point()> now)
    : max_(maxSessions), grace_(grace), now_(std::move(now)) {}

std::unique_ptr<SessionSlots::Slot> SessionSlots::enter() {
  std::function<void()> giveUp;
  std::unique_ptr<Slot> slot;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    const Clock::time_point now = now_();
    if (static_cast<int>(held_.size()) >= max_) {
      // Oldest first: the first idle one without a case gives its slot up.
      const auto idle = std::find_if(held_.begin(), held_.end(), [&](const Slot* s) {
        return s->giveUp_ && now - s->since_ >= grace_ && now - s->heard_ >= grace_ && !s->hasCase_();
      });
      if (idle == held_.end()) return nullptr;
      (*idle)->held_ = false;
      giveUp = (*idle)->giveUp_;
      held_.erase(idle);
    }
    slot.reset(new Slot(*this, now));
    held_.push_back(slot.get());
  }
  if (giveUp) giveUp();
  return slot;
}

int SessionSlots::taken() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return static_cast<int>(held_.size());
}

}  // namespace orthosim::server
