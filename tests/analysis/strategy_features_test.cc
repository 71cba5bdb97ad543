#include "analysis/strategy_features.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tests/analysis/strategy_swimmers.h"
#include "tests/analysis/synthetic_swimmer.h"

namespace animat::analysis {
namespace {

constexpr double kPi = std::numbers::pi;

template <typename Swimmer>
StrategyFeatures Measure(const Swimmer& swimmer) {
  Result<Recording> r = RecordingFromTrace(swimmer.Trace());
  EXPECT_TRUE(r.ok()) << r.status().ToString();
  if (!r.ok()) return {};
  Result<Analysis> a = Analyze(*r, {});
  EXPECT_TRUE(a.ok()) << a.status().ToString();
  if (!a.ok()) return {};
  return MeasureStrategyFeatures(*r, *a);
}

// Quadrant phases of a 4 × 2 grid: the back lags the front by Δ and the
// right the left by δ.
testing::SyntheticSwimmer Quadrants(double delta_back, double delta_right) {
  testing::SyntheticSwimmer swimmer;
  swimmer.heading = 2.0;
  for (int i = 0; i < swimmer.cells(); ++i) {
    double phase = 0;
    if (swimmer.BodyX(i) < 0) phase += delta_back;
    if (swimmer.BodyY(i) < 0) phase += delta_right;
    swimmer.phase.push_back(phase);
  }
  return swimmer;
}

TEST(StrategyFeaturesTest, SymmetryFollowsThePhaseLagBetweenSides) {
  // Equal amplitudes δ apart: 1 − |1 − e^{iδ}| / 2 = 1 − sin(δ/2).
  const StrategyFeatures f = Measure(Quadrants(0, kPi / 3));
  EXPECT_NEAR(*f.lr_symmetry, 0.5, 1e-4);
  EXPECT_NEAR(*f.fb_symmetry, 1, 1e-4);
  EXPECT_NEAR(*f.lr_lag, 1.0 / 6, 1e-4);
  EXPECT_NEAR(*f.fb_lag, 0, 1e-4);
  EXPECT_NEAR(*f.wave_across, 1, 1e-3);
  EXPECT_NEAR(*f.fb_amplitude_gradient, 0, 1e-4);
}

TEST(StrategyFeaturesTest, AWaveAlongTheMotionIsNotAcrossIt) {
  const StrategyFeatures f = Measure(Quadrants(-kPi / 2, 0));
  EXPECT_NEAR(*f.fb_lag, -0.25, 1e-4);
  EXPECT_NEAR(*f.wave_across, 0, 1e-3);
  EXPECT_NEAR(*f.lr_symmetry, 1, 1e-4);
  EXPECT_NEAR(*f.fb_symmetry, 1 - std::sin(kPi / 4), 1e-4);
}

TEST(StrategyFeaturesTest, AStrongerBackIsAnAmplitudeGradient) {
  testing::SyntheticSwimmer swimmer;
  for (int i = 0; i < swimmer.cells(); ++i) {
    swimmer.amplitude.push_back(swimmer.BodyX(i) < 0 ? 0.3 : 0.1);
  }
  const StrategyFeatures f = Measure(swimmer);
  EXPECT_NEAR(*f.fb_amplitude_gradient, 0.5, 1e-4);
  EXPECT_NEAR(*f.fb_symmetry, 0.5, 1e-4);
}

TEST(StrategyFeaturesTest, RectifiedActivityCannotTellSidesInAntiphase) {
  // The right half half a period after the left: opposite in e − c,
  // alike in |Δ(e − c)|.
  const StrategyFeatures antiphase = Measure(Quadrants(0, kPi));
  EXPECT_NEAR(*antiphase.lr_symmetry, 0, 1e-4);
  EXPECT_NEAR(*antiphase.lr_symmetry_rectified, 1, 1e-9);
  EXPECT_NEAR(*antiphase.fb_symmetry_rectified, 1, 1e-9);
  // A quarter period apart, the rectified curves are half of their own
  // period apart: |sin| against |cos|, less their means 2/π.
  const StrategyFeatures quarter = Measure(Quadrants(0, kPi / 2));
  EXPECT_NEAR(*quarter.lr_symmetry, 1 - std::sin(kPi / 4), 1e-4);
  const double apart = std::sqrt(1 - 2 / kPi);
  const double each = std::sqrt(0.5 - 4 / (kPi * kPi));
  EXPECT_NEAR(*quarter.lr_symmetry_rectified, 1 - apart / (2 * each), 0.01);
}

TEST(StrategyFeaturesTest, RectifiedSymmetrySeesAmplitude) {
  testing::SyntheticSwimmer swimmer;
  for (int i = 0; i < swimmer.cells(); ++i) {
    swimmer.amplitude.push_back(swimmer.BodyX(i) < 0 ? 0.3 : 0.1);
  }
  const StrategyFeatures f = Measure(swimmer);
  EXPECT_NEAR(*f.fb_symmetry_rectified, 0.5, 1e-9);
  EXPECT_NEAR(*f.lr_symmetry_rectified, 1, 1e-9);
}

TEST(StrategyFeaturesTest, SynchronyIsOneInStepAndZeroInAntiphase) {
  EXPECT_NEAR(*Measure(testing::SyntheticSwimmer()).synchrony, 1, 1e-9);
  const StrategyFeatures antiphase = Measure(Quadrants(kPi, 0));
  EXPECT_NEAR(*antiphase.synchrony, 0, 1e-9);
  // Two halves a quarter period apart: the mean's power is half of theirs.
  EXPECT_NEAR(*Measure(Quadrants(kPi / 2, 0)).synchrony, 0.5, 1e-3);
}

TEST(StrategyFeaturesTest, AllPeriodicWaveformsAreRegular) {
  EXPECT_LT(*Measure(testing::Jellyfish()).irregularity, 0.01);
  EXPECT_LT(*Measure(testing::SyntheticSwimmer()).irregularity, 1e-3);
  EXPECT_GT(*Measure(testing::Noise()).irregularity, 0.5);
}

TEST(StrategyFeaturesTest, TheJellyfishStrokeRisesSlowlyFallsFastAndHolds) {
  // Per period of 100 steps: 55 rising, 15 falling, 30 held.
  const StrategyFeatures f = Measure(testing::Jellyfish());
  EXPECT_NEAR(*f.rise_fraction, 55.0 / 70, 0.01);
  EXPECT_NEAR(*f.stroke_asymmetry, 40.0 / 70, 0.02);
  EXPECT_NEAR(*f.holding, 0.3, 0.01);
  const StrategyFeatures even = Measure(testing::Breather());
  EXPECT_NEAR(*even.rise_fraction, 0.5, 0.01);
  EXPECT_LT(*even.stroke_asymmetry, 0.02);
  EXPECT_LT(*even.holding, 0.05);
}

TEST(StrategyFeaturesTest, CoastingIsTheShareOfSlowSteps) {
  // Speed 0.002 before the contraction (u < 0.55), then a surge that
  // decays below half the mean (0.006) at u = 0.55 + 0.08 ln 50.
  const StrategyFeatures f = Measure(testing::Jellyfish());
  EXPECT_NEAR(*f.coasting, 0.55 + 1 - (0.55 + 0.08 * std::log(50.0)), 0.02);
  EXPECT_EQ(*Measure(testing::Breather()).coasting, 0);
}

TEST(StrategyFeaturesTest, ElongationComparesThePrincipalSpreads) {
  // A rigid 4 × 2 grid 2 apart: spreads √5 and 1.
  testing::SyntheticSwimmer grid;
  grid.breathing = 0;
  EXPECT_NEAR(*Measure(grid).elongation, 1 - 1 / std::sqrt(5.0), 1e-9);
  testing::SyntheticSwimmer chain;
  chain.rows = 1;
  chain.breathing = 0;
  const StrategyFeatures f = Measure(chain);
  EXPECT_NEAR(*f.elongation, 1, 1e-9);
  // A chain along its motion has no left or right.
  EXPECT_FALSE(f.lr_symmetry.has_value());
  EXPECT_FALSE(f.lr_lag.has_value());
  EXPECT_FALSE(f.wave_across.has_value());
  EXPECT_EQ(*f.end_taper, 0);
}

TEST(StrategyFeaturesTest, EndTaperSaysWhichEndIsPointed) {
  // Six cells abreast at the front, one at the back: the end quarters
  // hold the two widest rows (10 radii across) and the two narrowest (2).
  const StrategyFeatures pointed_back = Measure(testing::Jellyfish());
  EXPECT_NEAR(*pointed_back.end_taper, (2.0 - 10) / (2 + 10), 0.01);
  testing::PrescribedSwimmer reversed = testing::Jellyfish();
  for (Vec2& cell : reversed.body) cell.x = -cell.x;
  EXPECT_NEAR(*Measure(reversed).end_taper, (10.0 - 2) / (2 + 10), 0.01);
}

TEST(StrategyFeaturesTest,
     TheStrokeAgreesWithThePointedEndAsThePaperPairsThem) {
  // A pointed back that contracts fast (55 steps rising, 15 falling)
  // agrees; the same stroke with a pointed front does not.
  const StrategyFeatures pointed_back = Measure(testing::Jellyfish());
  EXPECT_NEAR(*pointed_back.stroke_agreement, 40.0 / 70, 0.02);
  testing::PrescribedSwimmer reversed = testing::Jellyfish();
  for (Vec2& cell : reversed.body) cell.x = -cell.x;
  EXPECT_NEAR(*Measure(reversed).stroke_agreement, -40.0 / 70, 0.02);
  // Ends alike say nothing.
  EXPECT_EQ(*Measure(testing::Jellyfish(testing::JellyfishVariant::kBlunt))
                 .stroke_agreement,
            0);
}

TEST(StrategyFeaturesTest, ASwingingTailIsABackProtrusion) {
  EXPECT_GT(*Measure(testing::Shark()).back_protrusion, 0.7);
  // A body that only scales moves its ends alike; a rigid one not at all.
  EXPECT_NEAR(*Measure(testing::Breather()).back_protrusion, 0.5, 1e-6);
  EXPECT_FALSE(
      Measure(testing::Shark(/*still_tail=*/true)).back_protrusion.has_value());
}

TEST(StrategyFeaturesTest, ConstantActuationHasOnlyShapeAndMotion) {
  testing::SyntheticSwimmer swimmer;
  swimmer.amplitude.assign(8, 0.0);
  const StrategyFeatures f = Measure(swimmer);
  EXPECT_FALSE(f.lr_symmetry.has_value());
  EXPECT_FALSE(f.synchrony.has_value());
  EXPECT_FALSE(f.irregularity.has_value());
  EXPECT_FALSE(f.stroke_asymmetry.has_value());
  EXPECT_TRUE(f.elongation.has_value());
  EXPECT_EQ(*f.coasting, 0);
  EXPECT_EQ(ClassifyStrategy(f).label, StrategyLabel::kOther);
}

}  // namespace
}  // namespace animat::analysis
