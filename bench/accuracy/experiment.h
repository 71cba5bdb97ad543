// Runs the whole measurement: the reference and every candidate on every
// animat, repeated for timing, and the one-ulp chaos runs.
#ifndef ANIMAT_BENCH_ACCURACY_EXPERIMENT_H_
#define ANIMAT_BENCH_ACCURACY_EXPERIMENT_H_

#include <ostream>
#include <string>
#include <vector>

#include "bench/accuracy/results.h"
#include "bench/accuracy/runner.h"
#include "common/base/status.h"

namespace animat::accuracy {

// The --quick run's animats: the first 4 random and the first evolved one
// by name (QuickSubset), so that CI exercises both kinds.
inline constexpr int kQuickRandom = 4;
inline constexpr int kQuickEvolved = 1;

struct ExperimentOptions {
  std::string data_dir;  // Genome files (LoadAnimatSet).
  // At most this many animats (the first by name); 0 for all, or for the
  // quick subset when `quick`.
  int max_animats = 0;
  // Timed repetitions of the whole candidate set (at least 1). Errors come
  // from the first; the others must give the same bits.
  int repeats = 3;
  // Recorded in the report; also skips the reference configuration's chaos
  // run and, unless max_animats is set, keeps only the quick subset
  // (kQuickRandom random and kQuickEvolved evolved animats).
  bool quick = false;
  std::ostream* progress = nullptr;  // Progress lines, or null.
  // Only the candidates with these labels (Candidate::Label, e.g. "R1f");
  // empty for the whole CandidateSet(). An unknown label is an error.
  std::vector<std::string> candidates;
  // physics.contact_near for the candidates with contact sub-steps
  // (negative: the model's default).
  double contact_near = -1.0;
  // physics.contact_stiffness (k_c) of every configuration, the reference
  // and the convergence check included (negative: the model's default).
  double contact_stiffness = -1.0;
};

// The chaos measurement's motion steps.
inline constexpr int kChaosSteps[] = {500, 1000, 2000, 4000, 6000};

// The errors (over the animats whose reference converged), failures and
// times of `result` from its animats' rows.
void Summarise(CandidateResult* result);

// Pairs of animats, both evaluated ok and both with a converged reference,
// that `runs` ranks in the opposite order from `reference` (all three
// indexed by animat); `pairs` receives how many pairs were compared.
int OrderSwaps(const std::vector<Run>& runs, const std::vector<Run>& reference,
               const std::vector<bool>& converged, int* pairs);

// docs/model.md §7.6: the label of the cheapest candidate (median ms per
// evaluation) that meets the rule (CandidateResult::MeetsRule), or "" when
// none does. Candidates within kRuleTimeTie of the cheapest count as equally
// cheap, and the one with the smallest 90th-percentile fitness error among
// them is chosen (the first of equals).
std::string RuleChoice(const std::vector<CandidateResult>& candidates);

// Runs everything single-threaded (so that timings are not disturbed by a
// second evaluation on the other core). Interleaves the candidates within
// each repetition so that a change of machine load affects them alike.
// Fails only if the animat set or the reference configuration cannot be
// loaded; a candidate that fails is a row with its error.
Result<Report> RunExperiment(const ExperimentOptions& options);

}  // namespace animat::accuracy

#endif  // ANIMAT_BENCH_ACCURACY_EXPERIMENT_H_
