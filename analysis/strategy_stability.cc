#include "analysis/strategy_stability.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "analysis/strategy_score.h"

namespace animat::analysis {
namespace {

// `value` moved by ± `fraction` of itself (of `width` when it is 0), kept
// within [lo, hi].
double Moved(double value, double width, double sign, double fraction,
             std::pair<double, double> range) {
  const double moved =
      value != 0 ? value * (1 + sign * fraction) : sign * fraction * width;
  return std::clamp(moved, range.first, range.second);
}

// Both moves of one end of rule `r` of label `i`.
void ShiftEnd(const StrategyFeatures& features, const StrategyRuleSet& rules,
              size_t i, size_t r, ThresholdShift::End end, double fraction,
              std::vector<ThresholdShift>* out) {
  const StrategyRule& rule = rules.required[i][r];
  const double width = std::abs(rule.to - rule.from);
  const std::pair<double, double> range =
      FeatureRange(rule.feature, rule.magnitude)
          .value_or(std::make_pair(-1e300, 1e300));
  for (double sign : {-1.0, 1.0}) {
    StrategyRuleSet changed = rules;
    StrategyRule& target = changed.required[i][r];
    double& value = end == ThresholdShift::End::kFrom ? target.from : target.to;
    ThresholdShift shift;
    shift.rule_label = kScoredLabels[i];
    shift.feature = rule.feature;
    shift.magnitude = rule.magnitude;
    shift.end = end;
    shift.original = value;
    value = Moved(value, width, sign, fraction, range);
    shift.moved = value;
    shift.label = ScoreStrategy(features, changed).label;
    out->push_back(shift);
  }
}

}  // namespace

std::vector<ThresholdShift> ShiftThresholds(const StrategyFeatures& features,
                                            const StrategyRuleSet& rules,
                                            double fraction) {
  std::vector<ThresholdShift> shifts;
  for (size_t i = 0; i < rules.required.size(); ++i) {
    for (size_t r = 0; r < rules.required[i].size(); ++r) {
      ShiftEnd(features, rules, i, r, ThresholdShift::End::kFrom, fraction,
               &shifts);
      ShiftEnd(features, rules, i, r, ThresholdShift::End::kTo, fraction,
               &shifts);
    }
  }
  for (double sign : {-1.0, 1.0}) {
    StrategyRuleSet changed = rules;
    changed.threshold =
        Moved(rules.threshold, 1.0, sign, fraction, std::make_pair(0.0, 1.0));
    ThresholdShift shift;
    shift.original = rules.threshold;
    shift.moved = changed.threshold;
    shift.label = ScoreStrategy(features, changed).label;
    shifts.push_back(shift);
  }
  return shifts;
}

std::string DescribeShift(const ThresholdShift& s) {
  char text[160];
  if (s.end == ThresholdShift::End::kThreshold) {
    std::snprintf(text, sizeof(text), "threshold %g → %g", s.original, s.moved);
    return text;
  }
  std::string feature = s.feature;
  if (s.magnitude) feature = '|' + feature + '|';
  std::snprintf(text, sizeof(text), "%s %s %s %g → %g",
                StrategyName(s.rule_label), feature.c_str(),
                s.end == ThresholdShift::End::kFrom ? "from" : "to", s.original,
                s.moved);
  return text;
}

}  // namespace animat::analysis
