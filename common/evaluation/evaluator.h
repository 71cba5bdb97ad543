// One evaluation of a genome (docs/model.md §8): network, development, body,
// equilibration, motion, fitness.
//
// Evaluate is a pure function of its arguments: the same genome and config
// give the same bits on every run and machine of one architecture. It never
// throws and never crashes on any genome or valid config; every failure is
// a status with a reason. Thread-safe: concurrent calls share nothing.
#ifndef ANIMAT_COMMON_EVALUATION_EVALUATOR_H_
#define ANIMAT_COMMON_EVALUATION_EVALUATOR_H_

#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "animat/v1/trace.pb.h"
#include "common/body/body.h"
#include "common/development/development.h"
#include "common/evaluation/model_config.h"
#include "common/genome/genome.h"
#include "common/physics/soft_body.h"

namespace animat {

enum class EvalStatus {
  kOk,
  kNonViable,         // No input-to-output path (model §2.5).
  kLateDivision,      // A division at or after last_division_step.
  kTooFewCells,       // Fewer than min_cells cells.
  kDegenerateBody,    // Coincident centres or no usable spring graph.
  kNumericalFailure,  // A non-finite or runaway value.
  kInvalidGenome,     // The genome failed ValidateGenome.
  // Nothing was simulated (never returned by Evaluate): a null-evaluation
  // worker.
  kNotEvaluated,
  // The evaluation crashed its process, alone too (never returned by
  // Evaluate: the master records it).
  kCrashed,
};

// "ok", "non_viable", "late_division", "too_few_cells", "degenerate_body",
// "numerical_failure", "invalid_genome", "not_evaluated", "crashed".
const char* EvalStatusName(EvalStatus status);

struct EvaluationResult {
  EvalStatus status = EvalStatus::kOk;
  std::string reason;  // Why, when status is not kOk.
  // What selection maximises (EvaluationParams::fitness): the distance
  // moved, or the distance within an energy budget; only when kOk.
  std::optional<double> fitness;
  int cells = 0;      // Cells at the end of development.
  int64_t steps = 0;  // Simulation steps run, all phases.
  // Hash of the bits of the final positions, velocities and network levels
  // (0 when motion did not run to the end).
  uint64_t state_hash = 0;
  // The body, once built (ok, a body without enough chambers, or a
  // numerical failure after development).
  std::optional<BodySummary> body;
  // The actuators' work over the motion phase (docs/model.md §10.1;
  // SoftBody::actuation_work), in the model's force times length units;
  // only when kOk.
  std::optional<double> energy;
  // The distance the centre of mass moved over the motion phase (radii);
  // only when kOk. Equals fitness under the paper's fitness.
  std::optional<double> distance;
};

v1::EvaluationResult EvaluationResultToProto(const EvaluationResult& result);

enum class MotionPhase { kEquilibration, kMotion };

// Receives the stages of an evaluation as they happen (traces, analysis).
// Called on the evaluating thread; references are valid only during the
// call.
class EvaluationObserver {
 public:
  virtual ~EvaluationObserver() = default;
  // After the mechanics of development step `step` (0-based).
  virtual void OnDevelopmentStep(int step, const Embryo& embryo) {
    (void)step;
    (void)embryo;
  }
  // The body built at the end of development, and the frozen actuation.
  virtual void OnBody(const Body& body, std::span<const double> expand,
                      std::span<const double> contract) {
    (void)body;
    (void)expand;
    (void)contract;
  }
  // After `step` steps of `phase` (step 0: the state as the phase starts).
  virtual void OnMotionStep(MotionPhase phase, int step,
                            const MotionState& state,
                            std::span<const double> expand,
                            std::span<const double> contract) {
    (void)phase;
    (void)step;
    (void)state;
    (void)expand;
    (void)contract;
  }
};

// Evaluates `genome` under `config` (which must have passed
// ConfigFromProto's checks). `observer` may be null.
EvaluationResult Evaluate(const Genome& genome, const ModelConfig& config,
                          EvaluationObserver* observer = nullptr);

}  // namespace animat

#endif  // ANIMAT_COMMON_EVALUATION_EVALUATOR_H_
