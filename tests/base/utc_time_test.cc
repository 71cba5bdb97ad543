// The one UTC timestamp format, of log lines and the lineage store.
#include "common/base/utc_time.h"

#include <gtest/gtest.h>

#include <chrono>
#include <regex>

namespace animat {
namespace {

using std::chrono::milliseconds;
using std::chrono::system_clock;

system_clock::time_point At(std::chrono::nanoseconds since_epoch) {
  return system_clock::time_point(
      std::chrono::duration_cast<system_clock::duration>(since_epoch));
}

TEST(UtcTimeTest, FormatsToTheMillisecond) {
  EXPECT_EQ(FormatUtc(At(milliseconds(0))), "1970-01-01T00:00:00.000Z");
  EXPECT_EQ(FormatUtc(At(milliseconds(1795269787123))),
            "2026-11-21T14:03:07.123Z");
  EXPECT_EQ(FormatUtc(At(milliseconds(1709251199999))),  // A leap day.
            "2024-02-29T23:59:59.999Z");
  EXPECT_EQ(FormatUtc(At(milliseconds(951868800000))),
            "2000-03-01T00:00:00.000Z");
}

TEST(UtcTimeTest, TruncatesToTheMillisecondNeverRoundingUp) {
  const auto last = At(std::chrono::nanoseconds(1709251199999999000));
  EXPECT_EQ(FormatUtc(last), "2024-02-29T23:59:59.999Z");
}

TEST(UtcTimeTest, TimesBeforeTheEpochCountBack) {
  EXPECT_EQ(FormatUtc(At(milliseconds(-1))), "1969-12-31T23:59:59.999Z");
  EXPECT_EQ(FormatUtc(At(std::chrono::nanoseconds(-1))),
            "1969-12-31T23:59:59.999Z");
  EXPECT_EQ(FormatUtc(At(milliseconds(-86400000))), "1969-12-31T00:00:00.000Z");
}

TEST(UtcTimeTest, NowHasTheSameShape) {
  const std::string now = UtcNow();
  EXPECT_TRUE(std::regex_match(
      now, std::regex(R"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d\.\d{3}Z)")))
      << now;
}

}  // namespace
}  // namespace animat
