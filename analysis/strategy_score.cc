#include "analysis/strategy_score.h"

#include <algorithm>

namespace animat::analysis {
namespace {

// p^(1/n) for p in (0, 1] by Newton's method from 1, which only
// decreases (converged for any p above 1e-200 with n <= 5): +, * and /
// alone, so the same bits on every machine, unlike libm's pow, exp, log.
double Root(double p, int n) {
  double x = 1;
  for (int iteration = 0; iteration < 500; ++iteration) {
    double power = 1;  // x^(n−1).
    for (int k = 1; k < n; ++k) power *= x;
    const double next = ((n - 1) * x + p / power) / n;
    if (!(next < x)) break;
    x = next;
  }
  return x;
}

std::vector<StrategyTerm> Terms(const std::vector<StrategyRule>& rules,
                                const StrategyFeatures& features) {
  std::vector<StrategyTerm> terms;
  for (const StrategyRule& rule : rules) {
    StrategyTerm term;
    term.feature = rule.feature;
    term.magnitude = rule.magnitude;
    term.value = FeatureValue(features, rule.feature);
    if (term.value) term.membership = Membership(rule, *term.value);
    terms.push_back(term);
  }
  return terms;
}

StrategyScore Score(StrategyLabel label, const StrategyFeatures& features,
                    const std::vector<StrategyRule>& rules) {
  StrategyScore score;
  score.label = label;
  score.terms = Terms(rules, features);
  score.descriptors = Terms(StrategyDescriptors(label), features);
  double product = rules.empty() ? 0.0 : 1.0;
  for (const StrategyTerm& term : score.terms) product *= term.membership;
  score.score =
      product > 0 ? Root(product, static_cast<int>(rules.size())) : 0.0;
  return score;
}

}  // namespace

StrategyVerdict ScoreStrategy(const StrategyFeatures& features,
                              const StrategyRuleSet& rules) {
  StrategyVerdict v;
  for (size_t i = 0; i < kScoredLabels.size(); ++i) {
    v.scores[i] = Score(kScoredLabels[i], features, rules.required[i]);
  }
  // Best and second best; ties go to the earlier label.
  size_t best = 0;
  for (size_t i = 1; i < v.scores.size(); ++i) {
    if (v.scores[i].score > v.scores[best].score) best = i;
  }
  double second = 0;
  for (size_t i = 0; i < v.scores.size(); ++i) {
    if (i != best) second = std::max(second, v.scores[i].score);
  }
  const double top = v.scores[best].score;
  if (top >= rules.threshold) {
    v.label = v.scores[best].label;
    v.margin = top - second;
  } else {
    v.label = StrategyLabel::kOther;
    v.margin = rules.threshold - top;
  }
  return v;
}

}  // namespace animat::analysis
