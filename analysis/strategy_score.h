// Scoring the swimming strategy's labels under a set of rules
// (analysis/strategy_rules.h): each required rule maps its feature to a
// membership, a label's score is the geometric mean of its memberships,
// so a label one of whose required traits is clearly absent scores 0, and
// the label is the best score if it reaches the rule set's threshold,
// else other. Descriptors are measured alongside and never scored. Pure
// functions of their arguments; deterministic; thread-safe.
#ifndef ANIMAT_ANALYSIS_STRATEGY_SCORE_H_
#define ANIMAT_ANALYSIS_STRATEGY_SCORE_H_

#include <array>
#include <optional>
#include <vector>

#include "analysis/strategy_rules.h"

namespace animat::analysis {

struct StrategyTerm {
  const char* feature = "";
  std::optional<double> value;  // Signed, as measured.
  double membership = 0;        // 0 when the feature is absent.
  bool magnitude = false;       // The rule reads |value|.
};

struct StrategyScore {
  StrategyLabel label = StrategyLabel::kOther;
  double score = 0;  // Geometric mean of the required memberships, [0, 1].
  std::vector<StrategyTerm> terms;        // One per required rule.
  std::vector<StrategyTerm> descriptors;  // One per descriptor; not scored.
};

// The label a rule set gives a feature vector.
struct StrategyVerdict {
  StrategyLabel label = StrategyLabel::kOther;
  // Best − second best score when labelled; threshold − best for other.
  double margin = 0;
  std::array<StrategyScore, 4> scores;  // In kScoredLabels' order.
};

// Scores every label by `rules` and picks one (ties go to the earlier
// label of kScoredLabels). Each score also lists the label's default
// descriptors (StrategyDescriptors), whatever `rules` holds.
StrategyVerdict ScoreStrategy(const StrategyFeatures& features,
                              const StrategyRuleSet& rules);

}  // namespace animat::analysis

#endif  // ANIMAT_ANALYSIS_STRATEGY_SCORE_H_
