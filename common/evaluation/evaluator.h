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
#include <vector>

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
  // only when kOk. Equals fitness under the paper's fitness. With guidance
  // (model §10.2), distance and energy are the means over the trials.
  std::optional<double> distance;
  // With guidance and kOk: the final distance from the centre of mass to
  // the source (radii), one per trial in trial order; otherwise empty.
  std::vector<double> source_distances;
  // The deepest overlap of two cells not joined by a spring (model §8.6,
  // v3): the largest (r_i + r_j - l) / (r_i + r_j) at the start of
  // equilibration and the end of every step of equilibration and motion
  // (every trial's, with guidance), 0 when none overlap; in [0, 1],
  // whatever the contact rule. Only when kOk.
  std::optional<double> max_overlap;
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
  // With guidance (model §10.2), before the motion of an observed trial:
  // its index, and every trial's chemical source (radii), in trial order.
  // Equilibration is observed once, before.
  virtual void OnGuidanceTrial(int trial, std::span<const Vec2> sources) {
    (void)trial;
    (void)sources;
  }
  // In motion step `step` (from 1), once the morphogen signals M (model
  // §5.2) are applied, before the network steps: `nodes[m]` is the unit
  // whose signal row m is, `signal[m * cells + i]` its M in cell i (in
  // [0, 1], or NaN). Only for the morphogens motion computes (model
  // §11.2), and not at all when it computes none.
  virtual void OnSignals(int step, std::span<const int> nodes, int cells,
                         std::span<const double> signal) {
    (void)step;
    (void)nodes;
    (void)cells;
    (void)signal;
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

// An experiment on one animat (docs/analysis.md, "Knock-outs"), not part of
// the model: one input silenced during motion only, so development and
// equilibration, and with them the body, are those of the intact animat.
struct Knockout {
  enum class Kind {
    kNone,       // Nothing silenced: the model's evaluation.
    kChemical,   // The CHEMICAL input reads 0 in every cell (model §10.2).
    kMorphogen,  // M_j of unit `node` reads 0 in every cell (model §5.2).
  };
  Kind kind = Kind::kNone;
  // With kMorphogen: the unit j, as a node index (model §2.1). A node that
  // makes no morphogen, or whose morphogen motion does not compute (model
  // §11.2), has no M_j to silence: the evaluation is then the intact one.
  int node = -1;
};

// How an evaluation runs. The result does not depend on it, except through
// `knockout`.
struct EvaluateOptions {
  // Threads for the guidance trials (model §10.2), >= 1: trials run
  // concurrently on copies of the equilibrated state and are summed in
  // trial order, so the bits are the same for every count. 1: all on the
  // calling thread.
  int threads = 1;
  // The guidance trial the observer sees, in [0, trials), or kAllTrials:
  // every trial in turn, in trial order, all on the calling thread.
  static constexpr int kAllTrials = -1;
  int observed_trial = 0;
  // What to silence during motion; kNone (the default) costs nothing and
  // leaves every bit of the model's evaluation as it is.
  Knockout knockout;
};

// Evaluates `genome` under `config` (which must have passed
// ConfigFromProto's checks). `observer` may be null; it is called on the
// calling thread only.
EvaluationResult Evaluate(const Genome& genome, const ModelConfig& config,
                          EvaluationObserver* observer = nullptr,
                          const EvaluateOptions& options = {});

// What Evaluate reads of `genome` under `config`: its network's Key
// (common/grn/network.h), or nullopt for a genome that is not valid
// (ValidateGenome), whose evaluation names its fault. Two genomes with
// equal keys evaluate, under `config`, to the same result bit for bit
// (default options): the master records one's evaluation for the other
// (docs/lineage.md). Thread-safe.
std::optional<std::string> EvaluationKey(const Genome& genome,
                                         const ModelConfig& config);

}  // namespace animat

#endif  // ANIMAT_COMMON_EVALUATION_EVALUATOR_H_
