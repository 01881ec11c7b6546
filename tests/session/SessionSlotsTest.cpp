// Session slots (session/SessionSlots): when every slot is taken, an idle connection without a
// case gives its slot to a new one; a fresh or talking one, or one with a case, never does.
#include <gtest/gtest.h>

#include "session/SessionSlots.hpp"

namespace orthosim::server {
namespace {
using namespace std::chrono_literals;

struct Connection {
  std::unique_ptr<SessionSlots::Slot> slot;
  bool hasCase = false;
  int closed = 0;
  void serve() {
    slot->whenNeeded([this] { return hasCase; }, [this] { ++closed; });
  }
};

TEST(SessionSlots, AnIdleConnectionWithoutACaseGivesItsSlotUp) {
  SessionSlots slots(3, 0ms);
  Connection withCase{slots.enter()}, idle{slots.enter()}, later{slots.enter()};
  ASSERT_TRUE(withCase.slot && idle.slot && later.slot);
  withCase.hasCase = true;
  for (Connection* c : {&withCase, &idle, &later}) c->serve();
  EXPECT_EQ(slots.taken(), 3);

  std::unique_ptr<SessionSlots::Slot> next = slots.enter();
  ASSERT_TRUE(next) << "the idle one made room";
  EXPECT_EQ(withCase.closed, 0) << "a session with a case is never closed to make room";
  EXPECT_EQ(idle.closed, 1) << "the oldest without a case";
  EXPECT_EQ(later.closed, 0);
  EXPECT_EQ(slots.taken(), 3);
  idle.slot.reset();
  EXPECT_EQ(slots.taken(), 3) << "a slot given up is not given back twice";

  later.hasCase = true;
  EXPECT_FALSE(slots.enter()) << "every slot holds a case, or has not started serving";
  EXPECT_EQ(later.closed, 0);
  next.reset();
  EXPECT_EQ(slots.taken(), 2);
  EXPECT_TRUE(slots.enter()) << "a slot given back";
}

TEST(SessionSlots, AFreshOrTalkingConnectionKeepsItsSlot) {
  SessionSlots fresh(1, 1h);
  Connection a{fresh.enter()};
  a.serve();
  EXPECT_FALSE(fresh.enter()) << "a new connection has the grace period to open its case";
  EXPECT_EQ(a.closed, 0);

  // A clock of the test's own, stepped past the grace period: the outcome does not hang on how
  // the machine schedules the test.
  SessionSlots::Clock::time_point now{};
  SessionSlots slots(1, 300ms, [&now] { return now; });
  Connection b{slots.enter()};
  b.serve();
  now += 299ms;
  EXPECT_FALSE(slots.enter()) << "still within the grace period";
  now += 101ms;
  b.slot->heard();  // its client just sent a message
  EXPECT_FALSE(slots.enter());
  EXPECT_EQ(b.closed, 0);
  now += 300ms;
  EXPECT_TRUE(slots.enter()) << "quiet for the grace period again";
  EXPECT_EQ(b.closed, 1);
}

TEST(SessionSlots, AConnectionThatOpenedItsCaseMeanwhileRejoins) {
  SessionSlots slots(1, 0ms);
  Connection a{slots.enter()};
  a.serve();
  std::unique_ptr<SessionSlots::Slot> b = slots.enter();
  ASSERT_TRUE(b);
  a.slot->rejoin();  // its open came in as the slot went
  EXPECT_EQ(slots.taken(), 2) << "over the limit until one ends";
  a.slot.reset();
  EXPECT_EQ(slots.taken(), 1);
}

}  // namespace
}  // namespace orthosim::server
