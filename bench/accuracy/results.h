// What the accuracy report measured, as plain values for the writers
// (report.h) and the plot (svg_plot.h).
#ifndef ANIMAT_BENCH_ACCURACY_RESULTS_H_
#define ANIMAT_BENCH_ACCURACY_RESULTS_H_

#include <cstdint>
#include <string>
#include <vector>

#include "bench/accuracy/candidates.h"

namespace animat::accuracy {

// One candidate on one animat. Errors are +infinity for a failed
// evaluation.
struct AnimatResult {
  std::string animat;
  std::string status;  // EvalStatusName.
  std::string reason;
  double fitness = 0.0;  // Meaningful when status is "ok".
  double reference_fitness = 0.0;
  double fitness_error = 0.0;     // |f - f_ref| / f_ref.
  double trajectory_error = 0.0;  // max_t |d(t) - d_ref(t)| / f_ref.
  double ms = 0.0;                // Median wall time over the repetitions.
  double cpu_ms = 0.0;            // Median CPU time of the evaluating thread.
  uint64_t state_hash = 0;
  bool deterministic = true;  // Every repetition gave the same bits.
  bool evolved = false;       // An evolved animat, not a random genome.
  double max_overlap = 0.0;   // Deepest unjoined overlap; when "ok".
  // Its reference converged (Report::converged); only such animats enter
  // the errors, percentiles and order swaps.
  bool converged = true;
};

struct CandidateResult {
  Candidate candidate;
  // Why it was not measured (the config reader's message), or why its
  // numbers are not a measurement of what it names ("no effect: ..."); empty
  // when it was measured.
  std::string error;
  std::vector<AnimatResult> animats;  // Empty when it could not be loaded.
  // Remarks that do not disqualify it ("bit-identical to E1 ...").
  std::string note;

  // For a float or Bullet candidate: the candidate that differs only in
  // that option (double, native), and |f - f_counterpart| / f_ref over the
  // animats (+infinity where either failed).
  std::string counterpart;
  double counterpart_median = 0.0, counterpart_p90 = 0.0, counterpart_max = 0.0;

  // Over the animats; failures count as +infinity.
  int failures = 0;
  double fitness_error_median = 0.0;
  double fitness_error_p90 = 0.0;
  double trajectory_error_median = 0.0;
  double trajectory_error_p90 = 0.0;
  double ms_median = 0.0;      // Over the animats' successful evaluations.
  double cpu_ms_median = 0.0;  // Likewise, CPU time.
  bool on_front = false;
  // Pairs of animats with a converged reference (both evaluated ok) that
  // this candidate ranks in the opposite order from the reference, out of
  // `order_pairs`: what selection would see.
  int order_swaps = 0;
  int order_pairs = 0;
  // The deepest unjoined overlap (docs/model.md §8.6) over its ok
  // evaluations, every animat of the set included.
  double max_overlap = 0.0;

  // Measured, every evaluation ok, options in effect: may be on the front.
  bool Eligible() const {
    return error.empty() && !animats.empty() && failures == 0;
  }
  // The accuracy rule for the default integrator (docs/model.md §7.6):
  // eligible, fitness error at most kRuleP90 at the 90th percentile, no
  // pair swapped, and no two unjoined cells of any animat overlapping by
  // more than kRuleOverlap (the default must hold the contact stiffness's
  // bound, §7.10, as well as the stiffness chosen under it).
  bool MeetsRule() const;
};

// The 90th-percentile fitness error the rule allows the default.
inline constexpr double kRuleP90 = 0.01;
// The deepest unjoined overlap the default may let through over the set,
// as a fraction of r_i + r_j: docs/model.md §7.10's bound (10%) with its
// margin 1.2 for a whole replication.
inline constexpr double kRuleOverlap = 0.10 / 1.2;
// An animat's reference has converged when |f_ref - f_check| is at most
// this fraction of f_check: ten times below the error the rule allows.
inline constexpr double kConvergenceTolerance = 1e-3;
// Median times within this fraction of the cheapest candidate that meets
// the rule count as equally cheap (the report's timing repeats to about
// this); among those the rule takes the most accurate.
inline constexpr double kRuleTimeTie = 0.05;

inline bool CandidateResult::MeetsRule() const {
  return Eligible() && fitness_error_p90 <= kRuleP90 && order_swaps == 0 &&
         max_overlap <= kRuleOverlap;
}

// Divergence of two runs whose dt differs by one ulp.
struct ChaosResult {
  std::string config;  // "default (E1)", "reference (R16)".
  std::vector<int> steps;
  // Over the animats, |d(t) - d'(t)| / f_ref at each of `steps`.
  std::vector<double> median, p90, max;
  // |f - f'| / f_ref over the animats.
  double fitness_median = 0.0, fitness_p90 = 0.0, fitness_max = 0.0;
  int animats = 0;
  int failures = 0;
};

struct Report {
  bool quick = false;
  int repeats = 0;
  std::vector<std::string> animats;  // Names, in order.
  // Per animat, in the same order: evolved (true) or a random genome. May
  // be empty: then all are random.
  std::vector<bool> evolved;
  // Animats left out because their reference evaluation failed.
  std::vector<std::string> excluded;
  std::string machine;  // CPU, cores, load average.
  double reference_ms_median = 0.0;
  std::vector<double> reference_fitness;  // Per animat, in order.
  // Per animat, in order: the deepest unjoined overlap under the reference
  // (docs/model.md §8.6), which the contact stiffness is chosen by.
  std::vector<double> reference_overlap;
  // The contact stiffness k_c every configuration ran with.
  double contact_stiffness = 0.0;
  // Per animat, in order: its fitness under the convergence check (RK4
  // with twice the reference's sub-steps), and whether the two agree within
  // kConvergenceTolerance. An animat whose reference does not converge has
  // no fitness to measure errors against: it is reported, and left out of
  // every candidate's errors and order swaps (docs/accuracy.md).
  std::vector<double> check_fitness;
  std::vector<bool> converged;
  std::vector<CandidateResult> candidates;
  std::vector<ChaosResult> chaos;
  double total_seconds = 0.0;
  // The label of the cheapest candidate (median ms per evaluation) that
  // meets the accuracy rule, or empty when none does.
  std::string rule_choice;
};

}  // namespace animat::accuracy

#endif  // ANIMAT_BENCH_ACCURACY_RESULTS_H_
