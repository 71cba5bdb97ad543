// Runs one evaluation, recording the centre of mass over the motion phase
// and the wall time, and compares runs with each other.
#ifndef ANIMAT_BENCH_ACCURACY_RUNNER_H_
#define ANIMAT_BENCH_ACCURACY_RUNNER_H_

#include <cstdint>
#include <string>
#include <vector>

#include "common/base/vec2.h"
#include "common/evaluation/evaluator.h"
#include "common/evaluation/model_config.h"
#include "common/genome/genome.h"

namespace animat::accuracy {

// The centre of mass is recorded every this many motion steps, and at the
// last one.
inline constexpr int kSampleInterval = 50;

struct Run {
  EvalStatus status = EvalStatus::kOk;
  std::string reason;    // Why, when not ok.
  double fitness = 0.0;  // Meaningful only when ok().
  // The deepest unjoined overlap (docs/model.md §8.6); meaningful only when
  // ok().
  double max_overlap = 0.0;
  uint64_t state_hash = 0;
  // Motion steps at which the centre of mass was recorded (0, 50, ...,
  // and the last), and its displacement from the start of motion then.
  std::vector<int> sample_step;
  std::vector<Vec2> displacement;
  double seconds = 0.0;      // Wall time of Evaluate (steady_clock).
  double cpu_seconds = 0.0;  // CPU time of this thread during Evaluate.

  bool ok() const { return status == EvalStatus::kOk; }
  // Same status, fitness bits and final-state hash.
  bool SameBits(const Run& other) const;
};

// Evaluates `genome` under `config` once and times it. Never throws.
Run RunEvaluation(const Genome& genome, const ModelConfig& config);

// |f - f_ref| / f_ref; +infinity when either run failed or f_ref is 0.
double FitnessError(const Run& run, const Run& reference);

// max over the recorded steps of |d(t) - d_ref(t)| / f_ref, where d is the
// displacement of the centre of mass from the start of motion; +infinity
// when either run failed, f_ref is 0 or the samples differ.
double TrajectoryError(const Run& run, const Run& reference);

// |d_a(step) - d_b(step)| / scale at one recorded step; +infinity when
// either run failed or did not record `step`.
double Divergence(const Run& a, const Run& b, int step, double scale);

}  // namespace animat::accuracy

#endif  // ANIMAT_BENCH_ACCURACY_RUNNER_H_
