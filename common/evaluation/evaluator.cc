#include "common/evaluation/evaluator.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <system_error>
#include <thread>
#include <vector>

#include "common/base/hash.h"
#include "common/development/signals.h"
#include "common/evaluation/chemical.h"
#include "common/grn/network.h"
#include "common/physics/bullet/bullet_stepper.h"

namespace animat {
namespace {

EvaluationResult Failure(EvalStatus status, std::string reason, int cells,
                         int64_t steps) {
  EvaluationResult result;
  result.status = status;
  result.reason = std::move(reason);
  result.cells = cells;
  result.steps = steps;
  return result;
}

// Each cell's EXPAND and CONTRACT values.
template <typename S>
void ReadActuation(const GrnBatchT<S>& grn, std::vector<double>* expand,
                   std::vector<double>* contract) {
  grn.OutputAll(OutputChannel::kExpand, expand->data());
  grn.OutputAll(OutputChannel::kContract, contract->data());
}

template <typename S>
void HashFinalState(const MotionState& state, const GrnBatchT<S>& grn,
                    StateHash* hash) {
  HashMotionState(state, hash);
  for (int node = 0; node < grn.network().node_count(); ++node) {
    for (int cell = 0; cell < grn.cells(); ++cell) {
      hash->AddDouble(grn.level(cell, node));
    }
  }
}

// What selection maximises (model §10.1): the distance, or the distance
// scaled down by the energy beyond the budget, d * (B / E).
double Objective(const EvaluationParams& ev, double distance, double energy) {
  if (ev.fitness == FitnessKind::kDistanceWithinEnergyBudget &&
      energy > ev.energy_budget) {
    return distance * (ev.energy_budget / energy);
  }
  return distance;
}

bool CheckDue(int step, int last, int interval) {
  return step % interval == 0 || step == last;
}

// The chemical of active guidance (model §10.2): a point source sensed by
// the skin cells.
struct Chemical {
  Vec2 source;
  double decay_length = 1.0;
  std::span<const int> skin_cells;  // Increasing; cells on a skin edge.
};

struct MotionOutcome {
  int64_t steps = 0;    // Motion steps run.
  std::string problem;  // Why it failed; "" when it ran to the end.
  // The deepest unjoined overlap at the end of any step (model §8.6).
  double max_overlap = 0.0;
};

// Shows the observer the signals motion step `step` applied.
template <typename S>
void ObserveSignals(int step, const GrnBatchT<S>& grn,
                    const MorphogenFieldT<S>& field,
                    EvaluationObserver* observer) {
  const int cells = grn.cells();
  std::vector<int> nodes;
  std::vector<double> signal;
  for (const int m : field.kept()) {
    nodes.push_back(grn.network().morphogen_nodes()[m]);
    const S* row = grn.signal_row(m);
    signal.insert(signal.end(), row, row + cells);
  }
  observer->OnSignals(step, nodes, cells, signal);
}

// The motion phase from `*state` (model §7.7, §8.1), with the CHEMICAL
// input recomputed before every network step when `chemical` is not null.
template <typename S>
MotionOutcome RunMotion(const ModelConfig& config, GrnBatchT<S>& grn,
                        MorphogenFieldT<S>& field, SoftBody& soft_body,
                        MotionStepper& stepper, MotionState* state,
                        const Chemical* chemical,
                        EvaluationObserver* observer) {
  const EvaluationParams& ev = config.evaluation;
  const int cells = grn.cells();
  const bool signalling = field.morphogens() > 0;
  std::vector<double> expand(cells), contract(cells), sensed;
  ReadActuation(grn, &expand, &contract);
  if (observer) {
    observer->OnMotionStep(MotionPhase::kMotion, 0, *state, expand, contract);
  }
  MotionOutcome outcome;
  const int history_base = config.development.steps;
  for (int step = 1; step <= ev.motion_steps; ++step) {
    if (signalling) {
      const int signal_step = history_base + step - 1;
      field.Record(signal_step, grn);
      field.Apply(signal_step, &grn);
      if (observer) ObserveSignals(step, grn, field, observer);
    }
    if (chemical) {
      SenseChemical(chemical->source, chemical->decay_length,
                    chemical->skin_cells, state->position, &sensed);
      grn.SetChemical(sensed);
    }
    grn.Step();
    ReadActuation(grn, &expand, &contract);
    soft_body.SetActuation(expand, contract);
    stepper.Step(state);
    ++outcome.steps;
    outcome.max_overlap =
        std::max(outcome.max_overlap, soft_body.DeepestUnjoinedOverlap(*state));
    if (CheckDue(step, ev.motion_steps, ev.check_interval)) {
      const std::string problem = CheckState(*state, ev.max_coordinate);
      if (!problem.empty()) {
        outcome.problem = problem + " at motion step " + std::to_string(step);
        return outcome;
      }
    }
    if (observer) {
      observer->OnMotionStep(MotionPhase::kMotion, step, *state, expand,
                             contract);
    }
  }
  return outcome;
}

// M_j of unit `node` reads 0 from now on, when the node makes a morphogen.
template <typename S>
void SilenceMorphogen(const Network& network, int node,
                      MorphogenFieldT<S>* field, GrnBatchT<S>* grn) {
  if (node < 0 || node >= network.node_count()) return;
  const int morphogen = network.nodes()[node].morphogen;
  if (morphogen >= 0) field->Silence(morphogen, grn);
}

struct TrialOutcome {
  MotionOutcome motion;
  double distance = 0.0;         // The centre of mass moved (radii).
  double energy = 0.0;           // Actuation work of the trial.
  double source_distance = 0.0;  // Final centre of mass to the source.
  uint64_t hash = 0;             // Final state and levels.
};

// Runs every guidance trial from copies of the equilibrated state (the
// development's network and signals, `soft_body`, `state`), on up to
// options.threads threads; the result is summed in trial order once all
// have finished, so it does not depend on the thread count. `max_overlap`:
// the deepest unjoined overlap of equilibration.
template <typename S>
EvaluationResult RunGuidanceTrials(
    const ModelConfig& config, const Body& body, const BodySummary& summary,
    const DevelopmentT<S>& development, const SoftBody& soft_body,
    const MotionState& state, int cells, int64_t steps, double max_overlap,
    EvaluationObserver* observer, const EvaluateOptions& options) {
  const GuidanceParams& g = config.guidance;
  const int trials = g.trials;
  const Vec2 start = CentreOfMass(state);
  const std::vector<int> skin = SkinCells(body);
  const bool watch_all =
      observer && options.observed_trial == EvaluateOptions::kAllTrials;
  const int observed = observer && !watch_all ? options.observed_trial : -1;
  std::vector<Vec2> sources(trials);
  for (int k = 0; k < trials; ++k) {
    sources[k] = GuidanceSource(start, k, trials, g.source_distance);
  }

  // A knock-out of the chemical (docs/analysis.md): no sensing, so every
  // cell's CHEMICAL reads the 0 it read during development.
  const bool sensing = options.knockout.kind != Knockout::Kind::kChemical;
  std::vector<TrialOutcome> outcomes(trials);
  auto run_trial = [&](int k) {
    Chemical chemical;
    chemical.source = sources[k];
    chemical.decay_length = g.decay_length;
    chemical.skin_cells = skin;
    GrnBatchT<S> grn = development.grn();
    MorphogenFieldT<S> field = development.field();
    SoftBody trial_body = soft_body;
    MotionState trial_state = state;
    // A Bullet world of its own (a fresh world per trial; contacts start
    // without the equilibration's cached manifolds).
    std::unique_ptr<MotionStepper> bullet;
    if (config.physics.backend == PhysicsBackend::kBullet) {
      bullet = MakeBulletStepper(&trial_body, body);
    }
    MotionStepper& stepper = bullet ? *bullet : trial_body;
    EvaluationObserver* watcher =
        watch_all || k == observed ? observer : nullptr;
    if (watcher) watcher->OnGuidanceTrial(k, sources);
    TrialOutcome& out = outcomes[k];
    out.motion =
        RunMotion(config, grn, field, trial_body, stepper, &trial_state,
                  sensing ? &chemical : nullptr, watcher);
    if (!out.motion.problem.empty()) return;
    const Vec2 end = CentreOfMass(trial_state);
    out.distance = Length(end - start);
    out.energy = trial_body.actuation_work();
    out.source_distance = Length(end - chemical.source);
    StateHash hash;
    HashFinalState(trial_state, grn, &hash);
    out.hash = hash.value();
  };

  const int threads =
      watch_all ? 1 : std::min(std::max(options.threads, 1), trials);
  if (threads == 1) {
    if (observed >= 0 && observed < trials) run_trial(observed);
    for (int k = 0; k < trials; ++k) {
      if (k == observed) continue;
      run_trial(k);
      if (!outcomes[k].motion.problem.empty()) break;  // Later ones unused.
    }
  } else {
    std::atomic<int> next{0};
    auto work = [&] {
      for (int k = next.fetch_add(1); k < trials; k = next.fetch_add(1)) {
        if (k != observed) run_trial(k);
      }
    };
    std::vector<std::thread> helpers;
    try {
      for (int t = 1; t < threads; ++t) helpers.emplace_back(work);
    } catch (const std::system_error&) {
      // No more threads: the ones started and this one share the trials.
    }
    // The observed trial on this thread: the observer is called on the
    // evaluating thread.
    if (observed >= 0 && observed < trials) run_trial(observed);
    work();
    for (std::thread& helper : helpers) helper.join();
  }

  // Trial order, whatever the threads: the first failure decides, and the
  // steps count up to it.
  StateHash hash;
  double score = 0.0, distance = 0.0, energy = 0.0;
  std::vector<double> source_distances;
  for (int k = 0; k < trials; ++k) {
    const TrialOutcome& out = outcomes[k];
    steps += out.motion.steps;
    if (!out.motion.problem.empty()) {
      EvaluationResult failure =
          Failure(EvalStatus::kNumericalFailure,
                  "trial " + std::to_string(k) + ": " + out.motion.problem,
                  cells, steps);
      failure.body = summary;
      return failure;
    }
    score += g.source_distance - out.source_distance;
    distance += out.distance;
    energy += out.energy;
    max_overlap = std::max(max_overlap, out.motion.max_overlap);
    source_distances.push_back(out.source_distance);
    hash.AddU64(out.hash);
  }
  score /= trials;
  distance /= trials;
  energy /= trials;
  const char* non_finite = !std::isfinite(score)      ? "non-finite fitness"
                           : !std::isfinite(distance) ? "non-finite distance"
                           : !std::isfinite(energy)   ? "non-finite energy"
                                                      : nullptr;
  if (non_finite) {
    EvaluationResult failure =
        Failure(EvalStatus::kNumericalFailure, non_finite, cells, steps);
    failure.body = summary;
    return failure;
  }
  EvaluationResult result;
  result.status = EvalStatus::kOk;
  result.fitness = score;
  result.distance = distance;
  result.energy = energy;
  result.source_distances = std::move(source_distances);
  result.max_overlap = max_overlap;
  result.cells = cells;
  result.steps = steps;
  result.state_hash = hash.value();
  result.body = summary;
  return result;
}

// Development, body, equilibration and motion of a viable network, with
// network arithmetic in S.
template <typename S>
EvaluationResult RunModel(const Network& network, const ModelConfig& config,
                          EvaluationObserver* observer,
                          const EvaluateOptions& options) {
  // Development (docs/model.md §4, §5).
  DevelopmentT<S> development(network, config.grn, config.development,
                              config.signals);
  typename DevelopmentT<S>::Observer on_step;
  if (observer) {
    on_step = [observer](int step, const DevelopmentT<S>& d) {
      observer->OnDevelopmentStep(step, d.embryo());
    };
  }
  const EvaluationParams& ev = config.evaluation;
  const DevelopmentOutcome outcome = development.Run(
      on_step, NumericalCheck{ev.max_coordinate, ev.check_interval});
  const Embryo& embryo = development.embryo();
  const int cells = embryo.cells();
  int64_t steps = outcome.steps_run;
  switch (outcome.status) {
    case DevelopmentStatus::kOk:
      break;
    case DevelopmentStatus::kLateDivision:
      return Failure(EvalStatus::kLateDivision, outcome.reason, cells, steps);
    case DevelopmentStatus::kTooFewCells:
      return Failure(EvalStatus::kTooFewCells, outcome.reason, cells, steps);
    case DevelopmentStatus::kNumericalFailure:
      return Failure(EvalStatus::kNumericalFailure, outcome.reason, cells,
                     steps);
  }

  // Body (model §6).
  Result<Body> body = BuildBody(embryo.position, embryo.radius);
  if (!body.ok()) {
    return Failure(EvalStatus::kDegenerateBody,
                   "degenerate body: " + body.status().message(), cells, steps);
  }
  const BodySummary summary = SummarizeBody(*body);
  // A body must enclose area (model §6.5, v2).
  const std::string shortfall = ChamberShortfall(summary, ev.min_chambers);
  if (!shortfall.empty()) {
    EvaluationResult failure =
        Failure(EvalStatus::kDegenerateBody, shortfall, cells, steps);
    failure.body = summary;
    return failure;
  }

  // Motion needs only what can influence EXPAND and CONTRACT; the other
  // nodes (DIVIDE, ROTATE, SIZE and what feeds only them) stop.
  constexpr OutputChannel kMotionOutputs[] = {OutputChannel::kExpand,
                                              OutputChannel::kContract};
  development.RestrictTo(network.NodesReaching(kMotionOutputs));

  // Positional information frozen at its end-of-development values
  // (model §5.3).
  GrnBatchT<S>& grn = development.grn();
  MorphogenFieldT<S>& field = development.field();
  for (int cell = 0; cell < cells; ++cell) {
    grn.SetInputs(
        cell, InputValuesAt(embryo.position[cell],
                            development.maternal_sources(), config.signals));
  }
  grn.FreezeInputs();
  const bool signalling = field.morphogens() > 0;
  if (signalling) field.SetGeometry(embryo.position);

  std::vector<double> expand(cells), contract(cells);
  ReadActuation(grn, &expand, &contract);
  SoftBody soft_body(*body, config.physics);
  soft_body.SetActuation(expand, contract);
  // The backend: SoftBody integrates itself, or a fresh Bullet world
  // integrates its forces.
  std::unique_ptr<MotionStepper> bullet;
  if (config.physics.backend == PhysicsBackend::kBullet) {
    bullet = MakeBulletStepper(&soft_body, *body);
  }
  MotionStepper& stepper = bullet ? *bullet : soft_body;
  MotionState state;
  state.position = body->position;
  state.velocity.assign(cells, Vec2{});
  double max_overlap = soft_body.DeepestUnjoinedOverlap(state);
  if (observer) {
    observer->OnBody(*body, expand, contract);
    observer->OnMotionStep(MotionPhase::kEquilibration, 0, state, expand,
                           contract);
  }

  // Equilibration: network stopped, velocities damped (model §8.2).
  for (int step = 1; step <= ev.equilibration_steps; ++step) {
    stepper.Step(&state);
    for (Vec2& v : state.velocity) v = v * ev.equilibration_damping;
    ++steps;
    max_overlap =
        std::max(max_overlap, soft_body.DeepestUnjoinedOverlap(state));
    if (CheckDue(step, ev.equilibration_steps, ev.check_interval)) {
      const std::string problem = CheckState(state, ev.max_coordinate);
      if (!problem.empty()) {
        EvaluationResult failure =
            Failure(EvalStatus::kNumericalFailure,
                    problem + " at equilibration step " + std::to_string(step),
                    cells, steps);
        failure.body = summary;
        return failure;
      }
    }
    if (observer) {
      observer->OnMotionStep(MotionPhase::kEquilibration, step, state, expand,
                             contract);
    }
  }

  // A knock-out of a morphogen (docs/analysis.md) starts with motion, once:
  // development and equilibration are the intact animat's.
  if (options.knockout.kind == Knockout::Kind::kMorphogen) {
    SilenceMorphogen(network, options.knockout.node, &field, &grn);
  }

  // Motion: network running (model §7.7, §8.1); energy counts from here
  // (model §10.1).
  for (Vec2& v : state.velocity) v = Vec2{};
  soft_body.ResetActuationWork();
  if (config.guidance.enabled) {
    return RunGuidanceTrials(config, *body, summary, development, soft_body,
                             state, cells, steps, max_overlap, observer,
                             options);
  }
  const Vec2 start = CentreOfMass(state);
  const MotionOutcome motion = RunMotion(config, grn, field, soft_body, stepper,
                                         &state, nullptr, observer);
  steps += motion.steps;
  if (!motion.problem.empty()) {
    EvaluationResult failure =
        Failure(EvalStatus::kNumericalFailure, motion.problem, cells, steps);
    failure.body = summary;
    return failure;
  }

  const double fitness = Length(CentreOfMass(state) - start);
  const double energy = soft_body.actuation_work();
  if (!std::isfinite(fitness) || !std::isfinite(energy)) {
    EvaluationResult failure = Failure(
        EvalStatus::kNumericalFailure,
        std::isfinite(fitness) ? "non-finite energy" : "non-finite fitness",
        cells, steps);
    failure.body = summary;
    return failure;
  }
  EvaluationResult result;
  result.status = EvalStatus::kOk;
  result.fitness = Objective(ev, fitness, energy);
  result.distance = fitness;
  result.energy = energy;
  result.max_overlap = std::max(max_overlap, motion.max_overlap);
  result.cells = cells;
  result.steps = steps;
  StateHash hash;
  HashFinalState(state, grn, &hash);
  result.state_hash = hash.value();
  result.body = summary;
  return result;
}

}  // namespace

const char* EvalStatusName(EvalStatus status) {
  switch (status) {
    case EvalStatus::kOk:
      return "ok";
    case EvalStatus::kNonViable:
      return "non_viable";
    case EvalStatus::kLateDivision:
      return "late_division";
    case EvalStatus::kTooFewCells:
      return "too_few_cells";
    case EvalStatus::kDegenerateBody:
      return "degenerate_body";
    case EvalStatus::kNumericalFailure:
      return "numerical_failure";
    case EvalStatus::kInvalidGenome:
      return "invalid_genome";
    case EvalStatus::kNotEvaluated:
      return "not_evaluated";
    case EvalStatus::kCrashed:
      return "crashed";
  }
  return "?";
}

v1::EvaluationResult EvaluationResultToProto(const EvaluationResult& r) {
  v1::EvaluationResult m;
  m.set_status(static_cast<v1::EvaluationResult::Status>(
      static_cast<int>(r.status) + v1::EvaluationResult::OK));
  m.set_reason(r.reason);
  if (r.fitness) m.set_fitness(*r.fitness);
  if (r.energy) m.set_energy(*r.energy);
  if (r.distance) m.set_distance(*r.distance);
  for (double d : r.source_distances) m.add_source_distances(d);
  if (r.max_overlap) m.set_max_overlap(*r.max_overlap);
  m.set_cells(r.cells);
  m.set_steps(r.steps);
  m.set_state_hash(r.state_hash);
  if (r.body) {
    v1::BodySummary* b = m.mutable_body();
    b->set_cells(r.body->cells);
    b->set_springs(r.body->springs);
    b->set_chambers(r.body->chambers);
    b->set_skin_edges(r.body->skin_edges);
    b->set_spread_major(r.body->spread_major);
    b->set_spread_minor(r.body->spread_minor);
  }
  return m;
}

EvaluationResult Evaluate(const Genome& genome, const ModelConfig& config,
                          EvaluationObserver* observer,
                          const EvaluateOptions& options) {
  Status valid = ValidateGenome(genome);
  if (!valid.ok()) {
    return Failure(EvalStatus::kInvalidGenome, valid.message(), 0, 0);
  }
  const Network network = Network::Build(genome, config.grn);
  const Viability viability = network.CheckViability();
  if (!viability.viable) {
    return Failure(EvalStatus::kNonViable, viability.reason, 0, 0);
  }
  if (config.grn.precision == Precision::kFloat) {
    return RunModel<float>(network, config, observer, options);
  }
  return RunModel<double>(network, config, observer, options);
}

}  // namespace animat
