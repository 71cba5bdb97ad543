// The swimming strategy of an animat, named after the paper's four
// (Brainless Bodies, "Results and Analysis"): turtle, shark, worm and
// jellyfish, or other (docs/analysis.md, "Strategy").
//
// Each label is scored from the traits the paper gives for its whole class
// (analysis/strategy_rules.h, analysis/strategy_score.h); the traits it
// reports of one individual are shown as descriptors. The symmetries are
// read from the sides' actuation, which decides, and from their rectified
// activity, whose label is reported beside. The label's stability is the
// label again with every threshold moved by ±20%
// (analysis/strategy_stability.h). Pure functions of their arguments;
// deterministic; thread-safe.
#ifndef ANIMAT_ANALYSIS_STRATEGY_H_
#define ANIMAT_ANALYSIS_STRATEGY_H_

#include <array>
#include <string>
#include <vector>

#include "analysis/strategy_rules.h"
#include "analysis/strategy_score.h"
#include "analysis/strategy_stability.h"
#include "animat/v1/analysis.pb.h"

namespace animat::analysis {

struct Strategy {
  StrategyLabel label = StrategyLabel::kOther;
  // Best − second best score when labelled; threshold − best for other.
  double margin = 0;
  std::array<StrategyScore, 4> scores;  // In kScoredLabels' order.
  StrategyFeatures features;
  // The label and margin with the rectified symmetries in place of the
  // actuation's (RectifiedReading); reported, not deciding.
  StrategyLabel rectified_label = StrategyLabel::kOther;
  double rectified_margin = 0;
  // Every threshold moved by ±kThresholdShift (ShiftThresholds).
  std::vector<ThresholdShift> shifts;

  // The shifts that change the label.
  std::vector<ThresholdShift> Sensitive() const;
};

// Scores every label by the default rules and picks one, with the
// rectified reading's label and the stability.
Strategy ClassifyStrategy(const StrategyFeatures& features);

void StrategyToProto(const Strategy& strategy, v1::StrategyAnalysis* out);
v1::StrategyAnalysis::Label StrategyLabelToProto(StrategyLabel label);
// Sets the fields of the features present.
void StrategyFeaturesToProto(const StrategyFeatures& features,
                             v1::StrategyFeatures* out);

// Two lines for people: the label and its margin; its stability, or the
// threshold moves that change it.
std::string StrategyHeadline(const Strategy& strategy);

// The headline, then each label's score with its terms (value →
// membership) and descriptors, the rectified reading's label, and the
// features.
std::string StrategySummary(const Strategy& strategy);

}  // namespace animat::analysis

#endif  // ANIMAT_ANALYSIS_STRATEGY_H_
