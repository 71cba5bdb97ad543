// Time for code that keeps deadlines (leases, heartbeats, liveness, commit
// intervals) or stamps records (the lineage store's times) behind a small
// interface, as LevelDB's Env does, so tests can run it on simulated time.
// Never used for anything that reaches results.
//
// Both clocks are thread-safe.
#ifndef ANIMAT_COMMON_BASE_CLOCK_H_
#define ANIMAT_COMMON_BASE_CLOCK_H_

#include <atomic>
#include <chrono>
#include <cstdint>

namespace animat {

class Clock {
 public:
  using TimePoint = std::chrono::steady_clock::time_point;

  virtual ~Clock() = default;
  // Monotonic: never earlier than a previous call.
  virtual TimePoint Now() const = 0;

  // Seconds since the clock's epoch, for rates and intervals.
  double Seconds() const {
    return std::chrono::duration<double>(Now().time_since_epoch()).count();
  }

  // Calendar time, for the times records carry (utc_time.h formats it).
  // Not monotonic on a real clock (the system's time may be set back).
  virtual std::chrono::system_clock::time_point Utc() const = 0;
};

// std::chrono::steady_clock, and std::chrono::system_clock for Utc. The
// object lives as long as the process.
const Clock& RealClock();

// Time that stands still until Advance moves it: for tests, which decide
// exactly when a lease expires or a peer has been silent long enough, and
// which times a record carries. Starts at the epoch (Utc: 1970-01-01
// 00:00:00 UTC). Code that waits on it for a time to pass waits until
// another thread advances it.
class ManualClock final : public Clock {
 public:
  TimePoint Now() const override {
    return TimePoint(
        std::chrono::nanoseconds(nanoseconds_.load(std::memory_order_acquire)));
  }
  std::chrono::system_clock::time_point Utc() const override {
    return std::chrono::system_clock::time_point(
        std::chrono::duration_cast<std::chrono::system_clock::duration>(
            std::chrono::nanoseconds(
                nanoseconds_.load(std::memory_order_acquire))));
  }
  // `by` >= 0.
  void Advance(std::chrono::nanoseconds by) {
    nanoseconds_.fetch_add(by.count(), std::memory_order_acq_rel);
  }

 private:
  std::atomic<int64_t> nanoseconds_{0};
};

}  // namespace animat

#endif  // ANIMAT_COMMON_BASE_CLOCK_H_
