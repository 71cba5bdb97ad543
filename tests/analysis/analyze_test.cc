#include "analysis/analyze.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "tests/analysis/synthetic_swimmer.h"

namespace animat::analysis {
namespace {

constexpr double kPi = std::numbers::pi;

// Quadrant phases: front-left 0, front-right δ, back-left Δ, back-right
// Δ + δ. The back then lags the front by Δ and the right the left by δ.
testing::SyntheticSwimmer Wave(double delta_back, double delta_right) {
  testing::SyntheticSwimmer swimmer;
  swimmer.heading = 2.0;
  swimmer.period = 80;
  for (int i = 0; i < swimmer.cells(); ++i) {
    double phase = 0;
    if (swimmer.BodyX(i) < 0) phase += delta_back;
    if (swimmer.BodyY(i) < 0) phase += delta_right;
    swimmer.phase.push_back(phase);
  }
  return swimmer;
}

Recording Record(const testing::SyntheticSwimmer& swimmer) {
  Result<Recording> r = RecordingFromTrace(swimmer.Trace());
  EXPECT_TRUE(r.ok()) << r.status().ToString();
  return r.ok() ? std::move(r).value() : Recording{};
}

TEST(AnalyzeTest, ATravellingWaveGivesItsPeriodAmplitudeAndLags) {
  const Recording r = Record(Wave(kPi / 2, -kPi / 3));
  Result<Analysis> a = Analyze(r, {});
  ASSERT_TRUE(a.ok()) << a.status().ToString();
  // The default window: the second half.
  EXPECT_EQ(a->from_step, 2000);
  EXPECT_EQ(a->to_step, 4000);
  ASSERT_TRUE(a->period_steps.has_value());
  EXPECT_NEAR(*a->period_steps, 80, 80 * 1e-5);
  EXPECT_GT(*a->periodic_fraction, 0.999);
  EXPECT_NEAR(*a->amplitude_mean, 0.3, 1e-4);
  EXPECT_NEAR(*a->amplitude_max, 0.3, 1e-4);
  ASSERT_TRUE(a->front_to_back.has_value());
  EXPECT_NEAR(a->front_to_back->radians, kPi / 2, 1e-4);
  EXPECT_NEAR(a->front_to_back->periods, 0.25, 1e-5);
  EXPECT_NEAR(a->front_to_back->steps, 20, 1e-3);
  ASSERT_TRUE(a->left_to_right.has_value());
  EXPECT_NEAR(a->left_to_right->radians, -kPi / 3, 1e-4);
  EXPECT_NEAR(a->left_to_right->periods, -1.0 / 6, 1e-5);
  // Each side's mean of two cosines δ apart has amplitude A cos(δ / 2).
  EXPECT_EQ(a->front.cells, 4);
  EXPECT_NEAR(a->front.actuation->amplitude, 0.3 * std::cos(kPi / 6), 1e-4);
  EXPECT_NEAR(a->left.actuation->amplitude, 0.3 * std::cos(kPi / 4), 1e-4);
  // Motion: 1e-3 radii per step, dt 0.05.
  EXPECT_NEAR(a->axes.body_frame_distance, 2.0, 1e-9);
  EXPECT_NEAR(a->speed, 1e-3 / 0.05, 1e-9);
  EXPECT_NEAR(*a->distance_per_cycle, 0.08, 1e-6);
  EXPECT_NEAR(a->axes.front.x, std::cos(2.0), 1e-9);
  // A cosine of amplitude A moves at a mean |rate| of 4A / T per step.
  EXPECT_NEAR(a->mean_activity, 4 * 0.3 / 80, 1e-4);
  EXPECT_NEAR(a->front.mean_activity, 4 * 0.3 / 80, 1e-4);
}

TEST(AnalyzeTest, AWaveFromBackToFrontHasANegativeLag) {
  const Recording r = Record(Wave(-0.4 * 2 * kPi, 0));
  Result<Analysis> a = Analyze(r, {});
  ASSERT_TRUE(a.ok()) << a.status().ToString();
  EXPECT_NEAR(a->front_to_back->periods, -0.4, 1e-5);
  EXPECT_NEAR(a->left_to_right->periods, 0, 1e-5);
}

TEST(AnalyzeTest, ACoarserRecordingGivesTheSamePeriodInSteps) {
  testing::SyntheticSwimmer swimmer = Wave(kPi / 2, 0);
  swimmer.stride = 4;
  const Recording r = Record(swimmer);
  Result<Analysis> a = Analyze(r, {.from_step = 1000, .to_step = 3000});
  ASSERT_TRUE(a.ok()) << a.status().ToString();
  EXPECT_EQ(a->from_step, 1000);
  EXPECT_EQ(a->to_step, 3000);
  EXPECT_EQ(a->stride, 4);
  EXPECT_NEAR(*a->period_steps, 80, 80 * 1e-5);
  EXPECT_NEAR(a->front_to_back->steps, 20, 1e-3);
}

TEST(AnalyzeTest, DriversAreTheFewestCellsWithHalfTheStroke) {
  testing::SyntheticSwimmer swimmer;
  swimmer.amplitude.assign(8, 0.1);
  swimmer.amplitude[5] = 0.4;  // Inner cell: springs of 6 radii in all.
  swimmer.amplitude[0] = 0.4;  // Corner cell: 4 radii.
  const Recording r = Record(swimmer);
  Result<Analysis> a = Analyze(r, {});
  ASSERT_TRUE(a.ok()) << a.status().ToString();
  // Strokes 0.2 × A × rest lengths: 0.48, 0.32, three corners at 0.08 and
  // three inner cells at 0.12, 1.4 in all; 0.48 + 0.32 >= 0.7.
  EXPECT_NEAR(*a->cells[5].stroke, 0.48, 1e-4);
  EXPECT_NEAR(*a->cells[0].stroke, 0.32, 1e-4);
  EXPECT_NEAR(*a->cells[1].stroke, 0.12, 1e-4);
  EXPECT_NEAR(*a->cells[3].stroke, 0.08, 1e-4);
  EXPECT_EQ(a->drivers, (std::vector<int>{5, 0}));
  EXPECT_TRUE(a->cells[5].driver);
  EXPECT_FALSE(a->cells[1].driver);
}

TEST(AnalyzeTest, ConstantActuationHasAxesButNoPeriod) {
  testing::SyntheticSwimmer swimmer;
  swimmer.amplitude.assign(8, 0.0);
  swimmer.breathing = 0;
  const Recording r = Record(swimmer);
  Result<Analysis> a = Analyze(r, {});
  ASSERT_TRUE(a.ok()) << a.status().ToString();
  EXPECT_FALSE(a->period_steps.has_value());
  EXPECT_FALSE(a->front_to_back.has_value());
  EXPECT_TRUE(a->drivers.empty());
  EXPECT_EQ(a->mean_activity, 0);
  const v1::Analysis proto = AnalysisToProto(*a, 1.5);
  EXPECT_FALSE(proto.has_period_steps());
  EXPECT_FALSE(proto.has_front_to_back());
  EXPECT_FALSE(proto.front().has_amplitude());
  EXPECT_DOUBLE_EQ(proto.fitness(), 1.5);
}

TEST(AnalyzeTest, TheProtoHoldsEveryCellAndTheLags) {
  const Recording r = Record(Wave(kPi / 2, -kPi / 3));
  Result<Analysis> a = Analyze(r, {});
  ASSERT_TRUE(a.ok());
  const v1::Analysis proto = AnalysisToProto(*a, std::nullopt);
  EXPECT_FALSE(proto.has_fitness());
  EXPECT_EQ(proto.cells(), 8);
  ASSERT_EQ(proto.cell_size(), 8);
  EXPECT_EQ(proto.cell(6).cell(), 6);
  // Cell 6: column 2, row 1 (x = 1, y = 1; breathing of 0.05 over 25
  // periods and one frame moves the mean by 0.05 / 2001).
  EXPECT_NEAR(proto.cell(6).along_front(), 1, 1e-4);
  EXPECT_NEAR(proto.cell(6).along_left(), 1, 1e-4);
  EXPECT_NEAR(proto.period_time(), 80 * 0.05, 1e-3);
  EXPECT_NEAR(proto.front_to_back().periods(), 0.25, 1e-5);
  EXPECT_EQ(proto.drivers_size(), static_cast<int>(a->drivers.size()));
  EXPECT_EQ(proto.front().cells() + proto.back().cells(), 8);
}

TEST(AnalyzeTest, TheDefaultWindowIsTheSecondHalfWhereTheAnimatActuates) {
  const Recording r = Record(Wave(kPi / 2, 0));
  Result<Analysis> a = Analyze(r, {});
  ASSERT_TRUE(a.ok()) << a.status().ToString();
  EXPECT_EQ(a->window_rule, WindowRule::kSecondHalf);
  EXPECT_EQ(a->from_step, 2000);
  EXPECT_EQ(a->to_step, 4000);
  ASSERT_TRUE(a->actuation.has_value());
  EXPECT_EQ(a->actuation->from, 0);
  EXPECT_EQ(a->actuation->to, 4000);
  EXPECT_EQ(DescribeWindow(*a),
            "motion steps 2000 to 4000 (the second half of the motion)");
  const v1::Analysis proto = AnalysisToProto(*a, std::nullopt);
  EXPECT_EQ(proto.window_rule(), v1::Analysis::SECOND_HALF);
  EXPECT_EQ(proto.actuation_to_step(), 4000);
}

// An animat whose actuation stops before the second half of the motion
// (here at step 1000) is analysed where it actuates, and says so.
TEST(AnalyzeTest, AnAnimatStillInTheSecondHalfIsAnalysedWhereItActuates) {
  testing::SyntheticSwimmer swimmer = Wave(kPi / 2, 0);
  swimmer.still_after = 1000;
  swimmer.stride = 4;
  const Recording r = Record(swimmer);
  Result<Analysis> a = Analyze(r, {});
  ASSERT_TRUE(a.ok()) << a.status().ToString();
  EXPECT_EQ(a->window_rule, WindowRule::kActuating);
  EXPECT_EQ(a->from_step, 0);
  EXPECT_EQ(a->to_step, 1000);
  EXPECT_TRUE(a->window_actuates);
  ASSERT_TRUE(a->period_steps.has_value());
  EXPECT_NEAR(*a->period_steps, 80, 0.5);
  EXPECT_GT(a->mean_activity, 0.01);
  EXPECT_EQ(DescribeWindow(*a),
            "motion steps 0 to 1000 (where the animat actuates: no cell does "
            "in the second half of the motion)");
  EXPECT_EQ(AnalysisToProto(*a, std::nullopt).window_rule(),
            v1::Analysis::ACTUATING);

  // A window asked for is kept, and says where the actuation is.
  Result<Analysis> asked =
      Analyze(r, {.from_step = 2000, .to_step = std::nullopt});
  ASSERT_TRUE(asked.ok()) << asked.status().ToString();
  EXPECT_EQ(asked->window_rule, WindowRule::kGiven);
  EXPECT_FALSE(asked->window_actuates);
  EXPECT_FALSE(asked->period_steps.has_value());
  EXPECT_EQ(asked->mean_activity, 0);
  EXPECT_EQ(DescribeWindow(*asked),
            "motion steps 2000 to 4000 (as asked); no cell actuates in it: the "
            "animat actuates in motion steps 0 to 1000 (--from 0 --to 1000)");

  // Actuation over less than half of the window is pointed out.
  Result<Analysis> wide = Analyze(r, {.from_step = 0, .to_step = std::nullopt});
  ASSERT_TRUE(wide.ok());
  EXPECT_EQ(DescribeWindow(*wide),
            "motion steps 0 to 4000 (as asked); the animat actuates in motion "
            "steps 0 to 1000 only");
}

TEST(AnalyzeTest, AnAnimatThatNeverActuatesIsSaidToBeSo) {
  testing::SyntheticSwimmer swimmer;
  swimmer.amplitude.assign(8, 0.0);
  const Recording r = Record(swimmer);
  Result<Analysis> a = Analyze(r, {});
  ASSERT_TRUE(a.ok()) << a.status().ToString();
  EXPECT_EQ(a->window_rule, WindowRule::kSecondHalf);
  EXPECT_FALSE(a->actuation.has_value());
  EXPECT_EQ(DescribeWindow(*a),
            "motion steps 2000 to 4000 (the second half of the motion); no "
            "cell actuates anywhere in the motion (no e − c changes by more "
            "than 0.0002 per step)");
  EXPECT_FALSE(AnalysisToProto(*a, std::nullopt).has_actuation_from_step());
}

TEST(AnalyzeTest, ABodyThatDoesNotMoveNamesTheWindow) {
  testing::SyntheticSwimmer swimmer;
  swimmer.speed = 0;
  swimmer.breathing = 0;
  const Recording r = Record(swimmer);
  Result<Analysis> a = Analyze(r, {});
  ASSERT_FALSE(a.ok());
  EXPECT_NE(a.status().message().find(
                "window: motion steps 2000 to 4000 (the second half of the "
                "motion); --from and --to choose another"),
            std::string::npos)
      << a.status().message();
}

TEST(AnalyzeTest, RejectsAWindowWithoutFrames) {
  testing::SyntheticSwimmer swimmer;
  swimmer.steps = 100;
  const Recording r = Record(swimmer);
  EXPECT_FALSE(Analyze(r, {.from_step = 90, .to_step = 10}).ok());
  EXPECT_FALSE(Analyze(r, {.from_step = 100, .to_step = 500}).ok());
  Result<Analysis> a = Analyze(r, {.from_step = 99, .to_step = 100});
  EXPECT_TRUE(a.ok()) << a.status().ToString();
  // An end past the recording is its last frame.
  Result<Analysis> end = Analyze(
      r, {.from_step = 50, .to_step = std::numeric_limits<int64_t>::max()});
  ASSERT_TRUE(end.ok()) << end.status().ToString();
  EXPECT_EQ(end->to_step, 100);
}

}  // namespace
}  // namespace animat::analysis
