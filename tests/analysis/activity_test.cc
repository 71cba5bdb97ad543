#include "analysis/activity.h"

#include <gtest/gtest.h>

#include "tests/analysis/synthetic_swimmer.h"

namespace animat::analysis {
namespace {

TEST(ActivityTest, IsTheAbsoluteChangeOfEMinusCPerStep) {
  testing::SyntheticSwimmer swimmer;
  swimmer.steps = 40;
  swimmer.stride = 4;
  Result<Recording> r = RecordingFromTrace(swimmer.Trace());
  ASSERT_TRUE(r.ok());
  for (int k = 1; k < r->frames(); ++k) {
    for (int i = 0; i < r->cells; ++i) {
      const double expected =
          std::abs(r->actuation(k, i) - r->actuation(k - 1, i)) / 4;
      EXPECT_DOUBLE_EQ(Activity(*r, k, i), expected);
    }
  }
  // A cell with (e, c) going from (0.5, 0.5) to (0.7, 0.4) over 4 steps:
  // e − c rose by 0.3.
  r->expand[1 * r->cells + 2] = 0.7;
  r->contract[1 * r->cells + 2] = 0.4;
  r->expand[0 * r->cells + 2] = 0.5;
  r->contract[0 * r->cells + 2] = 0.5;
  EXPECT_NEAR(Activity(*r, 1, 2), 0.3 / 4, 1e-15);
}

TEST(ActivityTest, EachSideAveragesOnlyItsOwnCells) {
  // Only the front-left cell (column 3, row 1) acts.
  testing::SyntheticSwimmer swimmer;
  swimmer.steps = 200;
  swimmer.amplitude.assign(8, 0.0);
  swimmer.amplitude[7] = 0.4;
  Result<Recording> r = RecordingFromTrace(swimmer.Trace());
  ASSERT_TRUE(r.ok());
  Result<BodyAxes> axes = FindBodyAxes(*r, {0, r->frames()});
  ASSERT_TRUE(axes.ok());
  const ActivitySeries s = ActivityAlongAxes(*r, *axes, {0, r->frames()});
  ASSERT_EQ(s.steps.size(), 200u);  // Activity starts at the second frame.
  EXPECT_EQ(s.steps.front(), 1);
  ASSERT_EQ(s.front.size(), 200u);
  ASSERT_EQ(s.right.size(), 200u);
  for (size_t k = 0; k < s.steps.size(); ++k) {
    const double cell = Activity(*r, static_cast<int>(k) + 1, 7);
    EXPECT_DOUBLE_EQ(s.front[k], cell / 4);  // 4 front cells.
    EXPECT_DOUBLE_EQ(s.left[k], cell / 4);   // 4 left cells.
    EXPECT_DOUBLE_EQ(s.back[k], 0);
    EXPECT_DOUBLE_EQ(s.right[k], 0);
    EXPECT_DOUBLE_EQ(s.all[k], cell / 8);
  }
}

TEST(ActivityTest, ASideWithoutCellsHasNoSeries) {
  // One row: every cell is on the front–back axis, none left or right.
  testing::SyntheticSwimmer swimmer;
  swimmer.rows = 1;
  swimmer.steps = 50;
  Result<Recording> r = RecordingFromTrace(swimmer.Trace());
  ASSERT_TRUE(r.ok());
  Result<BodyAxes> axes = FindBodyAxes(*r, {0, r->frames()});
  ASSERT_TRUE(axes.ok());
  const ActivitySeries s = ActivityAlongAxes(*r, *axes, {10, r->frames()});
  EXPECT_EQ(s.front.size(), s.steps.size());
  EXPECT_TRUE(s.left.empty());
  EXPECT_TRUE(s.right.empty());
}

}  // namespace
}  // namespace animat::analysis
