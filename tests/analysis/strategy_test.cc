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
  f.irregularity = 0.175;
  f.fb_lag = -0.05;
  return f;
}

StrategyFeatures FullJellyfish() {
  StrategyFeatures f;
  f.synchrony = 0.95;
  f.stroke_asymmetry = 0.4;
  f.stroke_agreement = 0.4;
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
    EXPECT_EQ(s.scores[i].descriptors.size(),
              StrategyDescriptors(kScoredLabels[i]).size());
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
  f.irregularity = 0.295;  // Membership 0.02: score cbrt(0.01) < 0.5.
  const Strategy s = ClassifyStrategy(f);
  EXPECT_EQ(s.label, StrategyLabel::kOther);
  EXPECT_NEAR(s.margin, kStrategyThreshold - std::cbrt(0.01), 1e-12);
}

TEST(StrategyTest, TheMarginIsTheLeadOverTheNextLabel) {
  StrategyFeatures f = FullJellyfish();
  f.lr_symmetry = 0.8;
  f.fb_symmetry = 0.75;
  f.irregularity = 0.175;
  const Strategy s = ClassifyStrategy(f);
  EXPECT_EQ(s.label, StrategyLabel::kJellyfish);
  EXPECT_EQ(ScoreOf(s, StrategyLabel::kJellyfish).score, 1);
  EXPECT_NEAR(s.margin, 1 - std::cbrt(0.25), 1e-12);
}

TEST(StrategyTest, DescriptorsAreShownButNotScored) {
  // The back-to-front wave of "most" turtles: a turtle either way.
  StrategyFeatures f = HalfTurtle();
  for (double lag : {-0.2, 0.0, 0.2}) {
    f.fb_lag = lag;
    const Strategy s = ClassifyStrategy(f);
    EXPECT_EQ(s.label, StrategyLabel::kTurtle) << lag;
    EXPECT_NEAR(ScoreOf(s, StrategyLabel::kTurtle).score, std::cbrt(0.25),
                1e-12);
    const StrategyTerm& wave =
        ScoreOf(s, StrategyLabel::kTurtle).descriptors[0];
    EXPECT_STREQ(wave.feature, "fb_lag");
    EXPECT_EQ(wave.membership, lag < 0 ? 1.0 : 0.0) << lag;
  }
  // Neither holding nor coasting: still a jellyfish.
  StrategyFeatures j = FullJellyfish();
  j.holding = 0;
  j.coasting = 0;
  EXPECT_EQ(ClassifyStrategy(j).label, StrategyLabel::kJellyfish);
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

TEST(StrategyTest, APointedEndAndAStrokeThatAgreesWithItMakeAJellyfish) {
  StrategyFeatures f = FullJellyfish();
  f.end_taper = 0.5;  // Either end may be the pointed one.
  EXPECT_EQ(ClassifyStrategy(f).label, StrategyLabel::kJellyfish);
  f.end_taper = 0;
  EXPECT_EQ(ClassifyStrategy(f).label, StrategyLabel::kOther);
  f = FullJellyfish();
  f.stroke_agreement = -0.4;  // The fast stroke at the wrong end.
  EXPECT_EQ(ClassifyStrategy(f).label, StrategyLabel::kOther);
}

TEST(StrategyTest, TheRectifiedReadingIsReportedButDoesNotDecide) {
  StrategyFeatures f = HalfTurtle();
  f.lr_symmetry = 0.1;             // Left and right in antiphase in e − c,
  f.lr_symmetry_rectified = 0.95;  // alike in activity.
  f.fb_symmetry_rectified = 0.7;
  const Strategy s = ClassifyStrategy(f);
  EXPECT_EQ(s.label, StrategyLabel::kOther);
  EXPECT_EQ(s.rectified_label, StrategyLabel::kTurtle);
  // Memberships 1, 2/3 and 0.5.
  EXPECT_NEAR(s.rectified_margin, std::cbrt(1.0 / 3), 1e-12);
}

TEST(StrategyTest, AStrongLabelSurvivesEveryThresholdMove) {
  StrategyFeatures f;
  f.lr_symmetry = 0.9;
  f.fb_symmetry = 0.5;
  f.irregularity = 0;
  const Strategy s = ClassifyStrategy(f);
  EXPECT_EQ(s.label, StrategyLabel::kTurtle);
  // Two moves of each end of each required rule, and of the threshold.
  size_t rules = 0;
  for (StrategyLabel label : kScoredLabels)
    rules += StrategyRules(label).size();
  EXPECT_EQ(s.shifts.size(), 4 * rules + 2);
  EXPECT_TRUE(s.Sensitive().empty());
}

TEST(StrategyTest, AWeakLabelNamesTheThresholdsThatUndoIt) {
  // lr_symmetry 0.56: membership 0.2, score cbrt(0.2) = 0.585. Its `from`
  // at 0.6 makes it 0, the threshold at 0.6 is above the score; its `to`
  // at 0.96 leaves cbrt(0.06 / 0.46) = 0.507.
  StrategyFeatures f;
  f.lr_symmetry = 0.56;
  f.fb_symmetry = 0.5;
  f.irregularity = 0;
  const Strategy s = ClassifyStrategy(f);
  ASSERT_EQ(s.label, StrategyLabel::kTurtle);
  const std::vector<ThresholdShift> sensitive = s.Sensitive();
  ASSERT_EQ(sensitive.size(), 2u);
  EXPECT_EQ(sensitive[0].rule_label, StrategyLabel::kTurtle);
  EXPECT_STREQ(sensitive[0].feature, "lr_symmetry");
  EXPECT_EQ(sensitive[0].end, ThresholdShift::End::kFrom);
  EXPECT_NEAR(sensitive[0].moved, 0.6, 1e-12);
  EXPECT_EQ(sensitive[0].label, StrategyLabel::kOther);
  EXPECT_EQ(DescribeShift(sensitive[0]), "turtle lr_symmetry from 0.5 → 0.6");
  EXPECT_EQ(sensitive[1].end, ThresholdShift::End::kThreshold);
  EXPECT_EQ(DescribeShift(sensitive[1]), "threshold 0.5 → 0.6");
}

// The moves of `feature`'s `end` in label `label`'s rules, down then up.
std::vector<ThresholdShift> MovesOf(const Strategy& s, StrategyLabel label,
                                    const std::string& feature,
                                    ThresholdShift::End end) {
  std::vector<ThresholdShift> moves;
  for (const ThresholdShift& shift : s.shifts) {
    if (shift.rule_label == label && shift.feature == feature &&
        shift.end == end) {
      moves.push_back(shift);
    }
  }
  return moves;
}

TEST(StrategyTest, AThresholdAtZeroMovesByAShareOfItsRamp) {
  // The jellyfish's |end_taper| ramp runs from 0 to 0.3: its `from` moves
  // up by 0.2 × 0.3, and down not at all (a magnitude is never below 0).
  const std::vector<ThresholdShift> moves =
      MovesOf(ClassifyStrategy(FullJellyfish()), StrategyLabel::kJellyfish,
              "end_taper", ThresholdShift::End::kFrom);
  ASSERT_EQ(moves.size(), 2u);
  EXPECT_TRUE(moves[0].magnitude);
  EXPECT_EQ(moves[0].original, 0);
  EXPECT_EQ(moves[0].moved, 0);
  EXPECT_NEAR(moves[1].moved, 0.2 * 0.3, 1e-12);
}

TEST(StrategyTest, AThresholdStaysWithinTheValuesItsFeatureTakes) {
  // A breather: both ends alike, so no turtle, even with the turtle's
  // fb_symmetry `from` moved up from 0.9, which stops at 1.
  StrategyFeatures f;
  f.lr_symmetry = 1;
  f.fb_symmetry = 1;
  f.irregularity = 0;
  const Strategy s = ClassifyStrategy(f);
  const std::vector<ThresholdShift> moves = MovesOf(
      s, StrategyLabel::kTurtle, "fb_symmetry", ThresholdShift::End::kFrom);
  ASSERT_EQ(moves.size(), 2u);
  EXPECT_NEAR(moves[0].moved, 0.72, 1e-12);
  EXPECT_EQ(moves[1].moved, 1);
  EXPECT_EQ(s.label, StrategyLabel::kOther);
  EXPECT_TRUE(s.Sensitive().empty());
  EXPECT_EQ(FeatureRange("end_taper", false), std::make_pair(-1.0, 1.0));
  EXPECT_EQ(FeatureRange("end_taper", true), std::make_pair(0.0, 1.0));
  EXPECT_FALSE(FeatureRange("no_such_feature", false).has_value());
}

TEST(StrategyTest, EveryRuleNamesAFeature) {
  StrategyFeatures all;
  for (const std::string& name : StrategyFeatureNames()) {
    EXPECT_FALSE(FeatureValue(all, name).has_value()) << name;
  }
  all.lr_symmetry = all.fb_symmetry = all.fb_lag = all.lr_lag = 0.5;
  all.fb_amplitude_gradient = all.wave_across = all.synchrony = 0.5;
  all.irregularity = all.rise_fraction = all.stroke_asymmetry = 0.5;
  all.holding = all.coasting = all.elongation = all.end_taper = 0.5;
  all.back_protrusion = all.lr_symmetry_rectified = 0.5;
  all.fb_symmetry_rectified = all.stroke_agreement = 0.5;
  for (const std::string& name : StrategyFeatureNames()) {
    EXPECT_TRUE(FeatureValue(all, name).has_value()) << name;
  }
  for (StrategyLabel label : kScoredLabels) {
    EXPECT_FALSE(StrategyRules(label).empty());
    EXPECT_FALSE(StrategyDescriptors(label).empty());
    for (const auto* rules :
         {&StrategyRules(label), &StrategyDescriptors(label)}) {
      for (const StrategyRule& rule : *rules) {
        EXPECT_TRUE(FeatureValue(all, rule.feature).has_value())
            << rule.feature;
        EXPECT_NE(rule.from, rule.to) << rule.feature;
      }
    }
  }
  EXPECT_TRUE(StrategyRules(StrategyLabel::kOther).empty());
  EXPECT_TRUE(StrategyDescriptors(StrategyLabel::kOther).empty());
  EXPECT_FALSE(FeatureValue(all, "no_such_feature").has_value());
}

TEST(StrategyTest, TheProtoHoldsLabelScoresTermsFeaturesAndShifts) {
  StrategyFeatures f = FullJellyfish();
  f.lr_lag = 0.125;
  f.lr_symmetry_rectified = 0.25;
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
  ASSERT_EQ(jellyfish.term_size(), 3);
  EXPECT_EQ(jellyfish.term(0).feature(), "synchrony");
  EXPECT_EQ(jellyfish.term(0).value(), 0.95);
  EXPECT_EQ(jellyfish.term(0).membership(), 1);
  EXPECT_TRUE(jellyfish.term(1).magnitude());  // |end_taper|.
  ASSERT_EQ(jellyfish.descriptor_term_size(), 3);
  EXPECT_EQ(jellyfish.descriptor_term(0).feature(), "holding");
  EXPECT_EQ(jellyfish.descriptor_term(0).value(), 0.25);
  EXPECT_FALSE(proto.score(0).term(0).has_value());  // No lr_symmetry.
  EXPECT_EQ(proto.features().lr_lag(), 0.125);
  EXPECT_EQ(proto.features().end_taper(), -0.5);
  EXPECT_EQ(proto.features().lr_symmetry_rectified(), 0.25);
  EXPECT_EQ(proto.features().stroke_agreement(), 0.4);
  EXPECT_FALSE(proto.features().has_lr_symmetry());
  EXPECT_EQ(proto.rectified_label(), v1::StrategyAnalysis::JELLYFISH);
  EXPECT_EQ(proto.shift_fraction(), kThresholdShift);
  ASSERT_EQ(proto.shift_size(), static_cast<int>(s.shifts.size()));
  EXPECT_TRUE(proto.stable());
  const v1::ThresholdShift& last = proto.shift(proto.shift_size() - 1);
  EXPECT_EQ(last.end(), v1::ThresholdShift::THRESHOLD);
  EXPECT_NEAR(last.moved(), 0.6, 1e-12);
  EXPECT_EQ(last.label(), v1::StrategyAnalysis::JELLYFISH);
  EXPECT_TRUE(last.survives());
}

TEST(StrategyTest, TheSummaryNamesTheLabelItsStabilityAndEachTerm) {
  const std::string text = StrategySummary(ClassifyStrategy(FullJellyfish()));
  EXPECT_EQ(text.rfind("strategy: jellyfish (margin 1.000", 0), 0u) << text;
  EXPECT_NE(text.find("stable: the label survives each of the"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("stroke_agreement +0.400 (1.00)"), std::string::npos)
      << text;
  EXPECT_NE(text.find("descriptors: holding +0.250 (1.00)"), std::string::npos)
      << text;
  EXPECT_NE(text.find("|end_taper| 0.500 (1.00)"), std::string::npos) << text;
  EXPECT_NE(text.find("lr_symmetry absent"), std::string::npos) << text;
  StrategyFeatures f = HalfTurtle();
  f.irregularity = 0.295;
  const std::string below = StrategySummary(ClassifyStrategy(f));
  EXPECT_EQ(below.rfind("strategy: other (no label reaches 0.50; the best is "
                        "0.285 below)",
                        0),
            0u)
      << below;
  // Score cbrt(0.09) = 0.448: a turtle with the threshold at 0.4.
  f.irregularity = 0.255;
  const std::string near = StrategySummary(ClassifyStrategy(f));
  EXPECT_NE(near.find("sensitive to "), std::string::npos) << near;
  EXPECT_NE(near.find("threshold 0.5 → 0.4 (turtle)"), std::string::npos)
      << near;
}

}  // namespace
}  // namespace animat::analysis
