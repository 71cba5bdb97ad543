// How stable a strategy label is: the label again with each threshold of
// the rules moved, one at a time, by a fraction of itself (docs/analysis.md,
// "Stability"). The thresholds are the `from` and `to` of every required
// rule and the score a label must reach; descriptors score nothing and are
// not moved. Pure function; deterministic; thread-safe.
#ifndef ANIMAT_ANALYSIS_STRATEGY_STABILITY_H_
#define ANIMAT_ANALYSIS_STRATEGY_STABILITY_H_

#include <string>
#include <vector>

#include "analysis/strategy_rules.h"

namespace animat::analysis {

// The thresholds are moved by this share of themselves, down and up.
inline constexpr double kThresholdShift = 0.2;

// One threshold moved, and the label that gives.
struct ThresholdShift {
  enum class End { kFrom, kTo, kThreshold };
  StrategyLabel rule_label = StrategyLabel::kOther;  // kOther for kThreshold.
  const char* feature = "";  // The rule's feature; "" for kThreshold.
  bool magnitude = false;    // The rule reads |feature|.
  End end = End::kThreshold;
  double original = 0;
  // original × (1 ± fraction); a threshold at 0 moves by ± fraction of its
  // ramp's width instead (|to − from|), so that it moves at all. Kept within
  // the values the rule's reading of its feature can take (FeatureRange):
  // a symmetry `from` at 0.9 moves to 0.72 and 1, not 1.08.
  double moved = 0;
  StrategyLabel label = StrategyLabel::kOther;  // With it moved.
};

// Every threshold of `rules` moved down, then up, by `fraction`, in the
// order of kScoredLabels, their rules, from before to, and the score
// threshold last; `features` classified again each time.
std::vector<ThresholdShift> ShiftThresholds(const StrategyFeatures& features,
                                            const StrategyRuleSet& rules,
                                            double fraction = kThresholdShift);

// "jellyfish synchrony from 0.6 → 0.72", "|lr_lag| to 0.1 → 0.08",
// "threshold 0.5 → 0.4".
std::string DescribeShift(const ThresholdShift& shift);

}  // namespace animat::analysis

#endif  // ANIMAT_ANALYSIS_STRATEGY_STABILITY_H_
