#include "analysis/strategy.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace animat::analysis {
namespace {

// A turtle's features with memberships 1, 0.5 and 0.5.
StrategyFeatures HalfTurtle() {
  StrategyFeatures f;
  f.lr_symmetry = 0.8;
  f.fb_symmetry = 0.75;
  f.fb_lag = -0.05;
  return f;
}

StrategyFeatures FullJellyfish() {
  StrategyFeatures f;
  f.synchrony = 0.95;
  f.stroke_asymmetry = 0.4;
  f.holding = 0.25;
  f.coasting = 0.3;
  f.end_taper = -0.5;
  return f;
}

const StrategyScore& ScoreOf(const Strategy& s, StrategyLabel label) {
  for (const StrategyScore& score : s.scores) {
    if (score.label == label) return score;
  }
  ADD_FAILURE() << "no score for " << StrategyName(label);
  return s.scores[0];
}

TEST(StrategyTest, ScoresAreInTheOrderOfTheLabels) {
  const Strategy s = ClassifyStrategy({});
  for (size_t i = 0; i < kScoredLabels.size(); ++i) {
    EXPECT_EQ(s.scores[i].label, kScoredLabels[i]);
    EXPECT_EQ(s.scores[i].terms.size(), StrategyRules(kScoredLabels[i]).size());
  }
}

TEST(StrategyTest, AScoreIsTheGeometricMeanOfItsMemberships) {
  const Strategy s = ClassifyStrategy(HalfTurtle());
  const StrategyScore& turtle = ScoreOf(s, StrategyLabel::kTurtle);
  ASSERT_EQ(turtle.terms.size(), 3u);
  EXPECT_STREQ(turtle.terms[0].feature, "lr_symmetry");
  EXPECT_NEAR(turtle.terms[0].membership, 1.0, 1e-12);
  EXPECT_NEAR(turtle.terms[1].membership, 0.5, 1e-12);
  EXPECT_NEAR(turtle.terms[2].membership, 0.5, 1e-12);
  EXPECT_NEAR(turtle.score, std::cbrt(0.25), 1e-12);
  EXPECT_EQ(s.label, StrategyLabel::kTurtle);
  // Nothing else scores: the margin is the whole score.
  EXPECT_NEAR(s.margin, std::cbrt(0.25), 1e-12);
}

TEST(StrategyTest, AnAbsentFeatureScoresItsLabelZero) {
  StrategyFeatures f = HalfTurtle();
  f.lr_symmetry.reset();
  const Strategy s = ClassifyStrategy(f);
  const StrategyScore& turtle = ScoreOf(s, StrategyLabel::kTurtle);
  EXPECT_FALSE(turtle.terms[0].value.has_value());
  EXPECT_EQ(turtle.terms[0].membership, 0);
  EXPECT_EQ(turtle.score, 0);
  EXPECT_EQ(s.label, StrategyLabel::kOther);
  EXPECT_EQ(s.margin, kStrategyThreshold);
}

TEST(StrategyTest, BelowTheThresholdIsOtherByTheDistanceToIt) {
  StrategyFeatures f = HalfTurtle();
  f.fb_lag = -0.002;  // Membership 0.02: score cbrt(0.01) < 0.5.
  const Strategy s = ClassifyStrategy(f);
  EXPECT_EQ(s.label, StrategyLabel::kOther);
  EXPECT_NEAR(s.margin, kStrategyThreshold - std::cbrt(0.01), 1e-12);
}

TEST(StrategyTest, TheMarginIsTheLeadOverTheNextLabel) {
  StrategyFeatures f = FullJellyfish();
  f.lr_symmetry = 0.8;
  f.fb_symmetry = 0.75;
  f.fb_lag = -0.05;
  const Strategy s = ClassifyStrategy(f);
  EXPECT_EQ(s.label, StrategyLabel::kJellyfish);
  EXPECT_EQ(ScoreOf(s, StrategyLabel::kJellyfish).score, 1);
  EXPECT_NEAR(s.margin, 1 - std::cbrt(0.25), 1e-12);
}

TEST(StrategyTest, AWaveFromFrontToBackIsNoTurtle) {
  StrategyFeatures f = HalfTurtle();
  f.fb_lag = 0.2;
  EXPECT_EQ(ClassifyStrategy(f).label, StrategyLabel::kOther);
}

TEST(StrategyTest, EitherDirectionAcrossCountsForTheShark) {
  StrategyFeatures f;
  f.back_protrusion = 0.8;
  f.fb_symmetry = 0.9;
  for (double lag : {-0.2, 0.2}) {
    f.lr_lag = lag;
    const Strategy s = ClassifyStrategy(f);
    EXPECT_EQ(s.label, StrategyLabel::kShark) << lag;
    EXPECT_EQ(s.margin, 1) << lag;
  }
}

TEST(StrategyTest, EitherPointedEndCountsForTheJellyfish) {
  StrategyFeatures f = FullJellyfish();
  f.end_taper = 0.5;
  EXPECT_EQ(ClassifyStrategy(f).label, StrategyLabel::kJellyfish);
  f.end_taper = 0;
  EXPECT_EQ(ClassifyStrategy(f).label, StrategyLabel::kOther);
}

TEST(StrategyTest, EveryRuleNamesAFeature) {
  StrategyFeatures all;
  for (auto member :
       {&StrategyFeatures::lr_symmetry, &StrategyFeatures::fb_symmetry,
        &StrategyFeatures::fb_lag, &StrategyFeatures::lr_lag,
        &StrategyFeatures::fb_amplitude_gradient,
        &StrategyFeatures::wave_across, &StrategyFeatures::synchrony,
        &StrategyFeatures::irregularity, &StrategyFeatures::rise_fraction,
        &StrategyFeatures::stroke_asymmetry, &StrategyFeatures::holding,
        &StrategyFeatures::coasting, &StrategyFeatures::elongation,
        &StrategyFeatures::end_taper, &StrategyFeatures::back_protrusion}) {
    all.*member = 0.5;
  }
  for (StrategyLabel label : kScoredLabels) {
    EXPECT_FALSE(StrategyRules(label).empty());
    for (const StrategyRule& rule : StrategyRules(label)) {
      EXPECT_TRUE(FeatureValue(all, rule.feature).has_value()) << rule.feature;
      EXPECT_NE(rule.from, rule.to) << rule.feature;
    }
  }
  EXPECT_TRUE(StrategyRules(StrategyLabel::kOther).empty());
  EXPECT_FALSE(FeatureValue(all, "no_such_feature").has_value());
}

TEST(StrategyTest, TheProtoHoldsLabelScoresTermsAndFeatures) {
  StrategyFeatures f = FullJellyfish();
  f.lr_lag = 0.125;
  const Strategy s = ClassifyStrategy(f);
  v1::StrategyAnalysis proto;
  StrategyToProto(s, &proto);
  EXPECT_EQ(proto.label(), v1::StrategyAnalysis::JELLYFISH);
  EXPECT_EQ(proto.margin(), s.margin);
  EXPECT_EQ(proto.threshold(), kStrategyThreshold);
  ASSERT_EQ(proto.score_size(), 4);
  EXPECT_EQ(proto.score(0).label(), v1::StrategyAnalysis::TURTLE);
  EXPECT_EQ(proto.score(1).label(), v1::StrategyAnalysis::SHARK);
  EXPECT_EQ(proto.score(2).label(), v1::StrategyAnalysis::WORM);
  const v1::StrategyScore& jellyfish = proto.score(3);
  EXPECT_EQ(jellyfish.label(), v1::StrategyAnalysis::JELLYFISH);
  EXPECT_EQ(jellyfish.score(), 1);
  ASSERT_EQ(jellyfish.term_size(), 5);
  EXPECT_EQ(jellyfish.term(0).feature(), "synchrony");
  EXPECT_EQ(jellyfish.term(0).value(), 0.95);
  EXPECT_EQ(jellyfish.term(0).membership(), 1);
  EXPECT_FALSE(proto.score(0).term(0).has_value());  // No lr_symmetry.
  EXPECT_EQ(proto.features().lr_lag(), 0.125);
  EXPECT_EQ(proto.features().end_taper(), -0.5);
  EXPECT_FALSE(proto.features().has_lr_symmetry());
}

TEST(StrategyTest, TheSummaryNamesTheLabelAndEachTerm) {
  const std::string text = StrategySummary(ClassifyStrategy(FullJellyfish()));
  EXPECT_EQ(text.rfind("strategy: jellyfish (margin 1.000", 0), 0u) << text;
  EXPECT_NE(text.find("stroke_asymmetry +0.400 (1.00)"), std::string::npos)
      << text;
  EXPECT_NE(text.find("lr_symmetry absent"), std::string::npos) << text;
  StrategyFeatures f = HalfTurtle();
  f.fb_lag = -0.002;
  const std::string below = StrategySummary(ClassifyStrategy(f));
  EXPECT_EQ(below.rfind("strategy: other (no label reaches 0.50; the best is "
                        "0.285 below)",
                        0),
            0u)
      << below;
}

}  // namespace
}  // namespace animat::analysis
