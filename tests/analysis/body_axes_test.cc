#include "analysis/body_axes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tests/analysis/synthetic_swimmer.h"

namespace animat::analysis {
namespace {

Recording Record(const testing::SyntheticSwimmer& swimmer) {
  Result<Recording> r = RecordingFromTrace(swimmer.Trace());
  EXPECT_TRUE(r.ok()) << r.status().ToString();
  return r.ok() ? std::move(r).value() : Recording{};
}

TEST(BodyAxesTest, TheFrontIsTheDirectionOfMotion) {
  testing::SyntheticSwimmer swimmer;
  swimmer.heading = 0.5;
  swimmer.steps = 399;  // 400 frames: 5 whole periods of breathing.
  const Recording r = Record(swimmer);
  Result<BodyAxes> axes = FindBodyAxes(r, {0, r.frames()});
  ASSERT_TRUE(axes.ok()) << axes.status().ToString();
  EXPECT_NEAR(axes->front.x, std::cos(0.5), 1e-9);
  EXPECT_NEAR(axes->front.y, std::sin(0.5), 1e-9);
  // Left is a quarter turn counter-clockwise from front.
  EXPECT_NEAR(axes->left.x, -std::sin(0.5), 1e-9);
  EXPECT_NEAR(axes->left.y, std::cos(0.5), 1e-9);
  EXPECT_NEAR(axes->displacement, 0.399, 1e-9);
  EXPECT_NEAR(axes->body_frame_distance, 0.399, 1e-9);
  EXPECT_NEAR(axes->rotation.back(), 0, 1e-9);
  for (int i = 0; i < r.cells; ++i) {
    // Breathing averages out over whole periods.
    EXPECT_NEAR(axes->along_front[i], swimmer.BodyX(i), 1e-9) << i;
    EXPECT_NEAR(axes->along_left[i], swimmer.BodyY(i), 1e-9) << i;
    EXPECT_EQ(axes->front_back[i],
              swimmer.BodyX(i) > 0 ? Side::kFront : Side::kBack);
    EXPECT_EQ(axes->left_right[i],
              swimmer.BodyY(i) > 0 ? Side::kLeft : Side::kRight);
  }
}

TEST(BodyAxesTest, CellsOnAnAxisAreOnNeitherSide) {
  // A 3 × 3 grid at a heading whose rotations round: its middle row and
  // column lie on the axes up to rounding.
  testing::SyntheticSwimmer swimmer;
  swimmer.columns = 3;
  swimmer.rows = 3;
  swimmer.heading = 0.7;
  swimmer.steps = 399;
  const Recording r = Record(swimmer);
  Result<BodyAxes> axes = FindBodyAxes(r, {0, r.frames()});
  ASSERT_TRUE(axes.ok()) << axes.status().ToString();
  for (int i = 0; i < r.cells; ++i) {
    EXPECT_EQ(axes->front_back[i] == Side::kNone, swimmer.BodyX(i) == 0) << i;
    EXPECT_EQ(axes->left_right[i] == Side::kNone, swimmer.BodyY(i) == 0) << i;
  }
}

TEST(BodyAxesTest, ATurningBodyKeepsItsOwnAxes) {
  // Three quarters of a turn while swimming forwards: the net displacement
  // points nowhere near the body's front, but the axes follow the body.
  testing::SyntheticSwimmer swimmer;
  swimmer.heading = -1.0;
  swimmer.steps = 3000;
  swimmer.turn_rate = 1.5 * std::numbers::pi / 3000;
  swimmer.breathing = 0;
  const Recording r = Record(swimmer);
  Result<BodyAxes> axes = FindBodyAxes(r, {0, r.frames()});
  ASSERT_TRUE(axes.ok()) << axes.status().ToString();
  EXPECT_NEAR(axes->front.x, std::cos(-1.0), 1e-6);
  EXPECT_NEAR(axes->front.y, std::sin(-1.0), 1e-6);
  EXPECT_NEAR(axes->rotation.back(), 1.5 * std::numbers::pi, 1e-9);
  EXPECT_NEAR(axes->body_frame_distance, 3.0, 1e-6);
  EXPECT_LT(axes->displacement, 3.0 * 0.7);
  // At the end the front has turned with the body.
  const Vec2 end_front = axes->FrontAt(r.frames() - 1);
  EXPECT_NEAR(end_front.x, std::cos(-1.0 + 1.5 * std::numbers::pi), 1e-6);
  EXPECT_NEAR(end_front.y, std::sin(-1.0 + 1.5 * std::numbers::pi), 1e-6);
  for (int i = 0; i < r.cells; ++i) {
    EXPECT_NEAR(axes->along_front[i], swimmer.BodyX(i), 1e-6) << i;
    EXPECT_NEAR(axes->along_left[i], swimmer.BodyY(i), 1e-6) << i;
  }
}

TEST(BodyAxesTest, ABodyThatDoesNotMoveHasNoAxes) {
  testing::SyntheticSwimmer swimmer;
  swimmer.speed = 0;
  swimmer.steps = 100;
  const Recording r = Record(swimmer);
  Result<BodyAxes> axes = FindBodyAxes(r, {0, r.frames()});
  ASSERT_FALSE(axes.ok());
  EXPECT_NE(axes.status().message().find("no direction of motion"),
            std::string::npos);
}

TEST(BodyAxesTest, RejectsAWindowOutsideTheRecording) {
  testing::SyntheticSwimmer swimmer;
  swimmer.steps = 100;
  const Recording r = Record(swimmer);
  EXPECT_FALSE(FindBodyAxes(r, {0, 1}).ok());
  EXPECT_FALSE(FindBodyAxes(r, {50, r.frames() + 1}).ok());
  EXPECT_FALSE(FindBodyAxes(r, {-1, 10}).ok());
}

TEST(BodyAxesTest, RotateTurnsCounterClockwise) {
  const Vec2 v = Rotate({1, 0}, std::numbers::pi / 2);
  EXPECT_NEAR(v.x, 0, 1e-15);
  EXPECT_NEAR(v.y, 1, 1e-15);
}

}  // namespace
}  // namespace animat::analysis
