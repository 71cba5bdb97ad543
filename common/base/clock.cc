#include "common/base/clock.h"

namespace animat {
namespace {

class SteadyClock final : public Clock {
 public:
  TimePoint Now() const override { return std::chrono::steady_clock::now(); }
  std::chrono::system_clock::time_point Utc() const override {
    return std::chrono::system_clock::now();
  }
};

}  // namespace

const Clock& RealClock() {
  static SteadyClock* const clock = new SteadyClock();  // Never destroyed.
  return *clock;
}

}  // namespace animat
