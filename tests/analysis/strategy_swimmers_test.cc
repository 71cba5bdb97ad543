// End to end: hand-made swimmers of known strategy, through Analyze, get
// their label with a positive margin; undoing one defining trait of each
// takes the label away.
#include <gtest/gtest.h>

#include "analysis/analyze.h"
#include "tests/analysis/strategy_swimmers.h"

namespace animat::analysis {
namespace {

Strategy Classify(const testing::PrescribedSwimmer& swimmer) {
  Result<Recording> r = RecordingFromTrace(swimmer.Trace());
  EXPECT_TRUE(r.ok()) << r.status().ToString();
  if (!r.ok()) return {};
  Result<Analysis> a = Analyze(*r, {});
  EXPECT_TRUE(a.ok()) << a.status().ToString();
  if (!a.ok()) return {};
  return a->strategy;
}

double ScoreOf(const Strategy& s, StrategyLabel label) {
  for (const StrategyScore& score : s.scores) {
    if (score.label == label) return score.score;
  }
  return -1;
}

TEST(StrategySwimmersTest, ATurtleIsATurtle) {
  const Strategy s = Classify(testing::Turtle());
  EXPECT_EQ(s.label, StrategyLabel::kTurtle) << StrategySummary(s);
  EXPECT_GT(s.margin, 0.3) << StrategySummary(s);
  EXPECT_LT(*s.features.fb_lag, -0.1);
  EXPECT_GT(*s.features.lr_symmetry, 0.99);
  EXPECT_GT(*s.features.fb_amplitude_gradient, 0);
}

TEST(StrategySwimmersTest, ATurtleWaveFromFrontToBackIsNoTurtle) {
  const Strategy s = Classify(testing::Turtle(/*wave_to_back=*/true));
  EXPECT_NE(s.label, StrategyLabel::kTurtle) << StrategySummary(s);
  EXPECT_GT(*s.features.fb_lag, 0.1);
  EXPECT_EQ(ScoreOf(s, StrategyLabel::kTurtle), 0);
}

TEST(StrategySwimmersTest, ASharkIsAShark) {
  const Strategy s = Classify(testing::Shark());
  EXPECT_EQ(s.label, StrategyLabel::kShark) << StrategySummary(s);
  EXPECT_GT(s.margin, 0.3) << StrategySummary(s);
  EXPECT_GT(*s.features.back_protrusion, 0.7);
  EXPECT_NEAR(*s.features.lr_lag, 0.25, 0.02);
}

TEST(StrategySwimmersTest, ASharkWithAStillTailIsNoShark) {
  const Strategy s = Classify(testing::Shark(/*still_tail=*/true));
  EXPECT_NE(s.label, StrategyLabel::kShark) << StrategySummary(s);
  EXPECT_EQ(ScoreOf(s, StrategyLabel::kShark), 0);
}

TEST(StrategySwimmersTest, AWormIsAWorm) {
  const Strategy s = Classify(testing::Worm());
  EXPECT_EQ(s.label, StrategyLabel::kWorm) << StrategySummary(s);
  EXPECT_GT(s.margin, 0.3) << StrategySummary(s);
  EXPECT_GT(*s.features.wave_across, 0.9);
  EXPECT_GT(*s.features.elongation, 0.6);
}

TEST(StrategySwimmersTest, ARegularWormIsNoWorm) {
  const Strategy s = Classify(testing::Worm(/*regular=*/true));
  EXPECT_NE(s.label, StrategyLabel::kWorm) << StrategySummary(s);
  EXPECT_LT(*s.features.irregularity, 0.01);
}

TEST(StrategySwimmersTest, AJellyfishIsAJellyfish) {
  const Strategy s = Classify(testing::Jellyfish());
  EXPECT_EQ(s.label, StrategyLabel::kJellyfish) << StrategySummary(s);
  EXPECT_GT(s.margin, 0.3) << StrategySummary(s);
  EXPECT_GT(*s.features.synchrony, 0.99);
  EXPECT_LT(*s.features.end_taper, -0.3);  // A pointed back.
}

TEST(StrategySwimmersTest, AnEvenStrokeOrABluntBodyIsNoJellyfish) {
  const Strategy even = Classify(testing::Jellyfish(/*sinusoidal=*/true));
  EXPECT_NE(even.label, StrategyLabel::kJellyfish) << StrategySummary(even);
  const Strategy blunt =
      Classify(testing::Jellyfish(/*sinusoidal=*/false, /*blunt=*/true));
  EXPECT_NE(blunt.label, StrategyLabel::kJellyfish) << StrategySummary(blunt);
  EXPECT_NEAR(*blunt.features.end_taper, 0, 1e-6);
}

TEST(StrategySwimmersTest, AnEvenBreatherIsOther) {
  const Strategy s = Classify(testing::Breather());
  EXPECT_EQ(s.label, StrategyLabel::kOther) << StrategySummary(s);
  EXPECT_GT(s.margin, 0.3) << StrategySummary(s);
}

TEST(StrategySwimmersTest, NoiseIsOther) {
  const Strategy s = Classify(testing::Noise());
  EXPECT_EQ(s.label, StrategyLabel::kOther) << StrategySummary(s);
  EXPECT_GT(s.margin, 0.3) << StrategySummary(s);
}

TEST(StrategySwimmersTest, TheLabelSurvivesACoarserRecordingAndAnotherHeading) {
  testing::PrescribedSwimmer jellyfish = testing::Jellyfish();
  jellyfish.stride = 2;
  jellyfish.heading = -2.5;
  EXPECT_EQ(Classify(jellyfish).label, StrategyLabel::kJellyfish);
  testing::PrescribedSwimmer turtle = testing::Turtle();
  turtle.stride = 4;
  turtle.heading = 3.0;
  EXPECT_EQ(Classify(turtle).label, StrategyLabel::kTurtle);
}

}  // namespace
}  // namespace animat::analysis
