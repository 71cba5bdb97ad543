// End to end: hand-made swimmers of known strategy, through Analyze, get
// their label with a positive margin, stably; undoing one trait the paper
// gives for the whole class takes the label away, while changing a trait it
// reports of one individual (a descriptor) does not.
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
  EXPECT_TRUE(s.Sensitive().empty()) << StrategySummary(s);
  EXPECT_EQ(s.rectified_label, StrategyLabel::kTurtle) << StrategySummary(s);
  EXPECT_LT(*s.features.fb_lag, -0.1);
  EXPECT_GT(*s.features.lr_symmetry, 0.99);
  EXPECT_GT(*s.features.fb_amplitude_gradient, 0);
}

TEST(StrategySwimmersTest, ATurtleWhoseWaveRunsFrontToBackIsStillATurtle) {
  // "In most of these individuals" the wave ran from the back: a
  // descriptor, which the reversed wave fails.
  const Strategy s =
      Classify(testing::Turtle(testing::TurtleVariant::kWaveToBack));
  EXPECT_EQ(s.label, StrategyLabel::kTurtle) << StrategySummary(s);
  EXPECT_GT(*s.features.fb_lag, 0.1);
  const StrategyScore& turtle = s.scores[0];
  ASSERT_EQ(turtle.label, StrategyLabel::kTurtle);
  ASSERT_FALSE(turtle.descriptors.empty());
  EXPECT_STREQ(turtle.descriptors[0].feature, "fb_lag");
  EXPECT_EQ(turtle.descriptors[0].membership, 0);
}

TEST(StrategySwimmersTest, SidesInAntiphaseAreATurtleOnlyWhenRectified) {
  const Strategy s =
      Classify(testing::Turtle(testing::TurtleVariant::kSidesAntiphase));
  EXPECT_NE(s.label, StrategyLabel::kTurtle) << StrategySummary(s);
  EXPECT_EQ(ScoreOf(s, StrategyLabel::kTurtle), 0) << StrategySummary(s);
  EXPECT_LT(*s.features.lr_symmetry, 0.1) << StrategySummary(s);
  EXPECT_GT(*s.features.lr_symmetry_rectified, 0.9) << StrategySummary(s);
  EXPECT_EQ(s.rectified_label, StrategyLabel::kTurtle) << StrategySummary(s);
}

TEST(StrategySwimmersTest, ASharkIsAShark) {
  const Strategy s = Classify(testing::Shark());
  EXPECT_EQ(s.label, StrategyLabel::kShark) << StrategySummary(s);
  EXPECT_GT(s.margin, 0.3) << StrategySummary(s);
  EXPECT_TRUE(s.Sensitive().empty()) << StrategySummary(s);
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
  EXPECT_TRUE(s.Sensitive().empty()) << StrategySummary(s);
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
  EXPECT_TRUE(s.Sensitive().empty()) << StrategySummary(s);
  EXPECT_GT(*s.features.synchrony, 0.99);
  EXPECT_LT(*s.features.end_taper, -0.3);        // A pointed back,
  EXPECT_GT(*s.features.stroke_agreement, 0.5);  // contracting fast.
}

TEST(StrategySwimmersTest, AJellyfishThatNeitherHoldsNorCoastsIsAJellyfish) {
  // Holding and coasting are the paper's one individual's: descriptors.
  const Strategy s =
      Classify(testing::Jellyfish(testing::JellyfishVariant::kSteady));
  EXPECT_EQ(s.label, StrategyLabel::kJellyfish) << StrategySummary(s);
  EXPECT_LT(*s.features.holding, 0.02);
  EXPECT_EQ(*s.features.coasting, 0);
}

TEST(StrategySwimmersTest, AnEvenStrokeOrABluntBodyIsNoJellyfish) {
  const Strategy even =
      Classify(testing::Jellyfish(testing::JellyfishVariant::kSinusoidal));
  EXPECT_NE(even.label, StrategyLabel::kJellyfish) << StrategySummary(even);
  const Strategy blunt =
      Classify(testing::Jellyfish(testing::JellyfishVariant::kBlunt));
  EXPECT_NE(blunt.label, StrategyLabel::kJellyfish) << StrategySummary(blunt);
  EXPECT_NEAR(*blunt.features.end_taper, 0, 1e-6);
}

TEST(StrategySwimmersTest, ADriftIsNoStroke) {
  // Every step rises, the body is synchronous and pointed: without the
  // need for a periodic actuation this would be a perfect jellyfish.
  const Strategy s =
      Classify(testing::Jellyfish(testing::JellyfishVariant::kDrift));
  EXPECT_NE(s.label, StrategyLabel::kJellyfish) << StrategySummary(s);
  EXPECT_GT(*s.features.synchrony, 0.99);
  EXPECT_GT(*s.features.irregularity, 0.5);
  EXPECT_FALSE(s.features.stroke_asymmetry.has_value());
  EXPECT_FALSE(s.features.stroke_agreement.has_value());
}

TEST(StrategySwimmersTest, AFastStrokeAtTheWrongEndIsNoJellyfish) {
  // A pointed back that expands fast: the paper pairs it with a fast
  // contraction.
  const Strategy s =
      Classify(testing::Jellyfish(testing::JellyfishVariant::kWrongStroke));
  EXPECT_NE(s.label, StrategyLabel::kJellyfish) << StrategySummary(s);
  EXPECT_LT(*s.features.end_taper, -0.3);
  EXPECT_GT(*s.features.stroke_asymmetry, 0.5);
  EXPECT_LT(*s.features.stroke_agreement, -0.5);
}

TEST(StrategySwimmersTest, AnEvenBreatherIsOther) {
  const Strategy s = Classify(testing::Breather());
  EXPECT_EQ(s.label, StrategyLabel::kOther) << StrategySummary(s);
  EXPECT_GT(s.margin, 0.3) << StrategySummary(s);
  EXPECT_TRUE(s.Sensitive().empty()) << StrategySummary(s);
}

TEST(StrategySwimmersTest, NoiseIsOther) {
  const Strategy s = Classify(testing::Noise());
  EXPECT_EQ(s.label, StrategyLabel::kOther) << StrategySummary(s);
  EXPECT_GT(s.margin, 0.3) << StrategySummary(s);
  EXPECT_TRUE(s.Sensitive().empty()) << StrategySummary(s);
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
