#include "common/base/utc_time.h"

#include <cstdio>

namespace animat {

std::string FormatUtc(std::chrono::system_clock::time_point time) {
  using std::chrono::days;
  using std::chrono::floor;
  using std::chrono::milliseconds;
  // floor, not a cast: before the epoch a cast would round towards it.
  const auto millis = floor<milliseconds>(time);
  const auto day = floor<days>(millis);
  const std::chrono::year_month_day date(day);
  const std::chrono::hh_mm_ss<milliseconds> clock(millis - day);
  char text[64];
  std::snprintf(text, sizeof(text), "%04d-%02u-%02uT%02d:%02d:%02d.%03dZ",
                static_cast<int>(date.year()),
                static_cast<unsigned>(date.month()),
                static_cast<unsigned>(date.day()),
                static_cast<int>(clock.hours().count()),
                static_cast<int>(clock.minutes().count()),
                static_cast<int>(clock.seconds().count()),
                static_cast<int>(clock.subseconds().count()));
  return text;
}

std::string UtcNow() { return FormatUtc(std::chrono::system_clock::now()); }

}  // namespace animat
