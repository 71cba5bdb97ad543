// The clocks behind common/base/clock.h: the real one follows
// steady_clock; the manual one stands still until advanced, also when
// another thread reads it meanwhile; both tell calendar time too.
#include "common/base/clock.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

namespace animat {
namespace {

using std::chrono::milliseconds;

TEST(ClockTest, RealClockFollowsTheSteadyClock) {
  const auto before = std::chrono::steady_clock::now();
  const Clock::TimePoint now = RealClock().Now();
  const auto after = std::chrono::steady_clock::now();
  EXPECT_LE(before, now);
  EXPECT_LE(now, after);
  EXPECT_EQ(&RealClock(), &RealClock());
}

TEST(ClockTest, ManualClockStandsStillUntilAdvanced) {
  ManualClock clock;
  const Clock::TimePoint start = clock.Now();
  EXPECT_EQ(start.time_since_epoch().count(), 0);
  EXPECT_EQ(clock.Now(), start);
  clock.Advance(milliseconds(250));
  EXPECT_EQ(clock.Now() - start, milliseconds(250));
  EXPECT_DOUBLE_EQ(clock.Seconds(), 0.25);
  clock.Advance(milliseconds(0));
  EXPECT_EQ(clock.Now() - start, milliseconds(250));
}

// Calendar time: the system clock's on the real clock; on the manual one,
// 1970-01-01 00:00:00 UTC moved by the same advances as Now.
TEST(ClockTest, UtcIsTheSystemClocksOrTheManualClocksFromTheEpoch) {
  const auto before = std::chrono::system_clock::now();
  const auto now = RealClock().Utc();
  const auto after = std::chrono::system_clock::now();
  EXPECT_LE(before, now);
  EXPECT_LE(now, after);
  ManualClock clock;
  EXPECT_EQ(clock.Utc().time_since_epoch().count(), 0);
  clock.Advance(milliseconds(1500));
  EXPECT_EQ(clock.Utc() - std::chrono::system_clock::time_point(),
            milliseconds(1500));
}

TEST(ClockTest, ManualClockIsAdvancedByOneThreadWhileAnotherReadsIt) {
  ManualClock clock;
  std::atomic<bool> done{false};
  std::thread reader([&] {
    Clock::TimePoint last = clock.Now();
    while (!done.load()) {
      const Clock::TimePoint now = clock.Now();
      EXPECT_GE(now, last);
      last = now;
    }
  });
  for (int i = 0; i < 10000; ++i) clock.Advance(std::chrono::microseconds(1));
  done.store(true);
  reader.join();
  EXPECT_EQ(clock.Now().time_since_epoch(), milliseconds(10));
}

}  // namespace
}  // namespace animat
