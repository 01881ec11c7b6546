#pragma once
// The session slots (--max-sessions) and who holds them. A connection that has not opened a case
// holds its slot only while nobody needs it: when a new connection finds every slot taken, the
// oldest connection without a case that has been quiet (no message from its client) for the
// grace period gives its slot up to it, and is closed with the reason. A fresh connection has the
// grace period to open its case; a session with a case open or opening is never made to give up.
// So idle connections, however many, cannot keep a surgeon out for longer than the grace period.
#include <chrono>
#include <functional>
#include <list>
#include <memory>
#include <mutex>

namespace orthosim::server {

class SessionSlots {
 public:
  using Clock = std::chrono::steady_clock;

  // One connection's slot; given back when destroyed, unless it was given up to another one.
  class Slot {
   public:
    ~Slot();
    Slot(const Slot&) = delete;
    Slot& operator=(const Slot&) = delete;

    // From the time the connection serves: `hasCase` says whether it has a case open or opening
    // (called under the slots' lock, from any thread: it must not call back into the slots);
    // `giveUp` closes it to make room (from any thread: it must hop onto the connection's own).
    void whenNeeded(std::function<bool()> hasCase, std::function<void()> giveUp);
    // A message from the client: the connection is not idle.
    void heard();
    // The connection opened a case while it was giving its slot up (a race of a few
    // microseconds): it keeps serving and takes a slot again, over the limit until one is freed.
    void rejoin();

   private:
    friend class SessionSlots;
    Slot(SessionSlots& slots, Clock::time_point since);

    SessionSlots& slots_;
    Clock::time_point since_;
    Clock::time_point heard_;
    std::function<bool()> hasCase_;
    std::function<void()> giveUp_;
    bool held_ = true;  // false once given up
  };

  // `now` is the clock the grace period is measured on (a test's own clock, to step past it).
  SessionSlots(int maxSessions, std::chrono::milliseconds grace, std::function<Clock::time_point()> now = Clock::now);

  // A free slot, or one an idle connection without a case gives up (its giveUp runs before this
  // returns); nullptr when neither is there.
  std::unique_ptr<Slot> enter();
  int taken() const;

 private:
  int max_;
  std::chrono::milliseconds grace_;
  std::function<Clock::time_point()> now_;
  mutable std::mutex mutex_;
  std::list<Slot*> held_;  // oldest first
};

}  // namespace orthosim::server
