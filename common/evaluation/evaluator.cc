#include "common/evaluation/evaluator.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <optional>
#include <span>
#include <string>
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

// Where an evaluation stands: what a failure at this point reports.
struct Progress {
  int cells = 0;
  int64_t steps = 0;
  std::optional<BodySummary> body;  // Once built.
};

// Every failure, in one place: its status and reason with the cells,
// steps and body reached (none before development).
EvaluationResult Failed(const Progress& p, EvalStatus status,
                        std::string reason) {
  EvaluationResult result;
  result.status = status;
  result.reason = std::move(reason);
  result.cells = p.cells;
  result.steps = p.steps;
  result.body = p.body;
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
  int64_t steps = 0;    // Lead and motion steps run.
  std::string problem;  // Why it failed; "" when it ran to the end.
  // The deepest unjoined overlap at the end of any step (model §8.6).
  double max_overlap = 0.0;
  // Sum over steps of SoftBody::HeldActuation(), when holding costs.
  double held = 0.0;
};

// E (model §10.1): the work of changing rest lengths, plus the holding
// cost when there is one (none: the work alone, bit for bit).
double Energy(const EvaluationParams& ev, const SoftBody& body,
              const MotionOutcome& motion) {
  const double work = body.actuation_work();
  return ev.holding_cost > 0.0 ? work + ev.holding_cost * motion.held : work;
}

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

// `lead` network steps with the body held still (docs/model.md §10.2),
// their signals at history steps `history_base` on, the CHEMICAL input
// sensed before each when `chemical` is not null.
template <typename S>
void RunLead(int lead, int history_base, GrnBatchT<S>& grn,
             MorphogenFieldT<S>& field, const MotionState& state,
             const Chemical* chemical) {
  std::vector<double> sensed;
  for (int step = 0; step < lead; ++step) {
    if (field.morphogens() > 0) {
      field.Record(history_base + step, grn);
      field.Apply(history_base + step, &grn);
    }
    if (chemical) {
      SenseChemical(chemical->source, chemical->decay_length,
                    chemical->skin_cells, state.position, &sensed);
      grn.SetChemical(sensed);
    }
    grn.Step();
  }
}

// The motion phase from `*state` (model §7.7, §8.1), after `lead` network
// steps with the body held, with the CHEMICAL input recomputed before every
// network step when `chemical` is not null.
template <typename S>
MotionOutcome RunMotion(const ModelConfig& config, GrnBatchT<S>& grn,
                        MorphogenFieldT<S>& field, SoftBody& soft_body,
                        MotionStepper& stepper, MotionState* state,
                        const Chemical* chemical, int lead,
                        EvaluationObserver* observer) {
  const EvaluationParams& ev = config.evaluation;
  const int cells = grn.cells();
  const bool signalling = field.morphogens() > 0;
  RunLead(lead, config.development.steps, grn, field, *state, chemical);
  std::vector<double> expand(cells), contract(cells), sensed;
  ReadActuation(grn, &expand, &contract);
  if (observer) {
    observer->OnMotionStep(MotionPhase::kMotion, 0, *state, expand, contract);
  }
  MotionOutcome outcome;
  outcome.steps = lead;
  const int history_base = config.development.steps + lead;
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
    if (ev.holding_cost > 0.0) outcome.held += soft_body.HeldActuation();
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

// Development's end as the evaluation's status.
EvalStatus StatusOf(DevelopmentStatus status) {
  switch (status) {
    case DevelopmentStatus::kOk:
      return EvalStatus::kOk;
    case DevelopmentStatus::kLateDivision:
      return EvalStatus::kLateDivision;
    case DevelopmentStatus::kTooFewCells:
      return EvalStatus::kTooFewCells;
    case DevelopmentStatus::kNumericalFailure:
      break;
  }
  return EvalStatus::kNumericalFailure;
}

// What the motion phase measured, however many trials it had.
struct Swum {
  double fitness = 0.0;
  double distance = 0.0;
  double energy = 0.0;
  double max_overlap = 0.0;
  uint64_t state_hash = 0;
  std::vector<double> source_distances;  // With guidance.
};

// The result of a motion that ran to its end: ok, or a numerical failure
// when a number it reports is not finite.
EvaluationResult Finished(const Progress& p, Swum swum) {
  const char* non_finite = !std::isfinite(swum.fitness) ? "non-finite fitness"
                           : !std::isfinite(swum.distance)
                               ? "non-finite distance"
                           : !std::isfinite(swum.energy) ? "non-finite energy"
                                                         : nullptr;
  if (non_finite) return Failed(p, EvalStatus::kNumericalFailure, non_finite);
  EvaluationResult result;
  result.status = EvalStatus::kOk;
  result.fitness = swum.fitness;
  result.distance = swum.distance;
  result.energy = swum.energy;
  result.source_distances = std::move(swum.source_distances);
  result.max_overlap = swum.max_overlap;
  result.cells = p.cells;
  result.steps = p.steps;
  result.state_hash = swum.state_hash;
  result.body = p.body;
  return result;
}

struct TrialOutcome {
  MotionOutcome motion;
  double distance = 0.0;         // The centre of mass moved (radii).
  double energy = 0.0;           // Actuation work of the trial.
  double source_distance = 0.0;  // Final centre of mass to the source.
  uint64_t hash = 0;             // Final state and levels.
};

// Runs trial(k) for every k < trials on up to `threads` threads, `first`
// (when in range) on this thread before its share of the others; alone,
// it stops at the first trial that fails (the later ones would not be
// used).
template <typename RunTrial>
void RunEveryTrial(int trials, int threads, int first, RunTrial run_trial,
                   const std::vector<TrialOutcome>& outcomes) {
  const bool has_first = first >= 0 && first < trials;
  if (threads == 1) {
    if (has_first) run_trial(first);
    for (int k = 0; k < trials; ++k) {
      if (k == first) continue;
      run_trial(k);
      if (!outcomes[k].motion.problem.empty()) break;
    }
    return;
  }
  std::atomic<int> next{0};
  auto work = [&] {
    for (int k = next.fetch_add(1); k < trials; k = next.fetch_add(1)) {
      if (k != first) run_trial(k);
    }
  };
  std::vector<std::thread> helpers;
  try {
    for (int t = 1; t < threads; ++t) helpers.emplace_back(work);
  } catch (const std::system_error&) {
    // No more threads: the ones started and this one share the trials.
  }
  if (has_first) run_trial(first);
  work();
  for (std::thread& helper : helpers) helper.join();
}

// The evaluation of a viable network, with network arithmetic in S, as a
// pipeline: develop, build the body, equilibrate, then swim once or the
// guidance trials. Each phase returns a failure or nothing; Failed and
// Finished make every result. Lives on the stack of one evaluation: its
// members are borrowed by the steppers, so it is never moved.
template <typename S>
class Pipeline {
 public:
  Pipeline(const Network& network, const ModelConfig& config,
           EvaluationObserver* observer, const EvaluateOptions& options)
      : network_(network),
        config_(config),
        ev_(config.evaluation),
        observer_(observer),
        options_(options),
        development_(network, config.grn, config.development, config.signals) {}
  Pipeline(const Pipeline&) = delete;
  Pipeline& operator=(const Pipeline&) = delete;

  EvaluationResult Run() {
    if (auto failed = Develop()) return *failed;
    if (auto failed = BuildTheBody()) return *failed;
    PrepareMotion();
    if (auto failed = Equilibrate()) return *failed;
    StartMotion();
    return config_.guidance.enabled ? GuidanceTrials() : Swim();
  }

 private:
  using Failure = std::optional<EvaluationResult>;

  // Development (model §4, §5).
  Failure Develop() {
    typename DevelopmentT<S>::Observer on_step;
    if (observer_) {
      on_step = [this](int step, const DevelopmentT<S>& d) {
        observer_->OnDevelopmentStep(step, d.embryo());
      };
    }
    const DevelopmentOutcome outcome = development_.Run(
        on_step, NumericalCheck{ev_.max_coordinate, ev_.check_interval});
    progress_.cells = development_.embryo().cells();
    progress_.steps = outcome.steps_run;
    if (outcome.status == DevelopmentStatus::kOk) return std::nullopt;
    return Failed(progress_, StatusOf(outcome.status), outcome.reason);
  }

  // The body (model §6), which must enclose area (§6.5, v2).
  Failure BuildTheBody() {
    const Embryo& embryo = development_.embryo();
    Result<Body> body = BuildBody(embryo.position, embryo.radius);
    if (!body.ok()) {
      return Failed(progress_, EvalStatus::kDegenerateBody,
                    "degenerate body: " + body.status().message());
    }
    body_ = std::move(body).value();
    progress_.body = SummarizeBody(*body_);
    const std::string shortfall =
        ChamberShortfall(*progress_.body, ev_.min_chambers);
    if (shortfall.empty()) return std::nullopt;
    return Failed(progress_, EvalStatus::kDegenerateBody, shortfall);
  }

  // The network and body as motion needs them: only the nodes that can
  // influence EXPAND and CONTRACT (DIVIDE, ROTATE, SIZE and what feeds only
  // them stop), positional information frozen at its end-of-development
  // values (model §5.3), the soft body at rest under the first actuation.
  void PrepareMotion() {
    constexpr OutputChannel kMotionOutputs[] = {OutputChannel::kExpand,
                                                OutputChannel::kContract};
    development_.RestrictTo(network_.NodesReaching(kMotionOutputs));
    const Embryo& embryo = development_.embryo();
    GrnBatchT<S>& grn = development_.grn();
    for (int cell = 0; cell < progress_.cells; ++cell) {
      grn.SetInputs(cell, InputValuesAt(embryo.position[cell],
                                        development_.maternal_sources(),
                                        config_.signals));
    }
    grn.FreezeInputs();
    if (development_.field().morphogens() > 0) {
      development_.field().SetGeometry(embryo.position);
    }
    expand_.resize(progress_.cells);
    contract_.resize(progress_.cells);
    ReadActuation(grn, &expand_, &contract_);
    soft_body_.emplace(*body_, config_.physics);
    soft_body_->SetActuation(expand_, contract_);
    // The backend: SoftBody integrates itself, or a fresh Bullet world
    // integrates its forces.
    if (config_.physics.backend == PhysicsBackend::kBullet) {
      bullet_ = MakeBulletStepper(&*soft_body_, *body_);
    }
    state_.position = body_->position;
    state_.velocity.assign(progress_.cells, Vec2{});
    max_overlap_ = soft_body_->DeepestUnjoinedOverlap(state_);
    if (observer_) {
      observer_->OnBody(*body_, expand_, contract_);
      observer_->OnMotionStep(MotionPhase::kEquilibration, 0, state_, expand_,
                              contract_);
    }
  }

  MotionStepper& stepper() {
    return bullet_ ? *bullet_ : static_cast<MotionStepper&>(*soft_body_);
  }

  // Equilibration: network stopped, velocities damped (model §8.2).
  Failure Equilibrate() {
    for (int step = 1; step <= ev_.equilibration_steps; ++step) {
      stepper().Step(&state_);
      for (Vec2& v : state_.velocity) v = v * ev_.equilibration_damping;
      ++progress_.steps;
      max_overlap_ =
          std::max(max_overlap_, soft_body_->DeepestUnjoinedOverlap(state_));
      if (CheckDue(step, ev_.equilibration_steps, ev_.check_interval)) {
        const std::string problem = CheckState(state_, ev_.max_coordinate);
        if (!problem.empty()) {
          return Failed(
              progress_, EvalStatus::kNumericalFailure,
              problem + " at equilibration step " + std::to_string(step));
        }
      }
      if (observer_) {
        observer_->OnMotionStep(MotionPhase::kEquilibration, step, state_,
                                expand_, contract_);
      }
    }
    return std::nullopt;
  }

  // Motion starts at rest with the work uncounted (model §10.1); a
  // knock-out of a morphogen (docs/analysis.md) starts here, once:
  // development and equilibration are the intact animat's.
  void StartMotion() {
    if (options_.knockout.kind == Knockout::Kind::kMorphogen) {
      SilenceMorphogen(network_, options_.knockout.node, &development_.field(),
                       &development_.grn());
    }
    for (Vec2& v : state_.velocity) v = Vec2{};
    soft_body_->ResetActuationWork();
  }

  // Motion: network running (model §7.7, §8.1).
  EvaluationResult Swim() {
    const Vec2 start = CentreOfMass(state_);
    GrnBatchT<S>& grn = development_.grn();
    const MotionOutcome motion =
        RunMotion(config_, grn, development_.field(), *soft_body_, stepper(),
                  &state_, nullptr, 0, observer_);
    progress_.steps += motion.steps;
    if (!motion.problem.empty()) {
      return Failed(progress_, EvalStatus::kNumericalFailure, motion.problem);
    }
    Swum swum;
    swum.distance = Length(CentreOfMass(state_) - start);
    swum.energy = Energy(ev_, *soft_body_, motion);
    swum.fitness = swum.distance;
    if (std::isfinite(swum.distance) && std::isfinite(swum.energy)) {
      swum.fitness = Objective(ev_, swum.distance, swum.energy);
    }
    swum.max_overlap = std::max(max_overlap_, motion.max_overlap);
    StateHash hash;
    HashFinalState(state_, grn, &hash);
    swum.state_hash = hash.value();
    return Finished(progress_, std::move(swum));
  }

  // One guidance trial from a copy of the equilibrated network, signals,
  // body and state, towards source k.
  void RunTrial(int k, const std::vector<Vec2>& sources,
                std::span<const int> skin, Vec2 start,
                EvaluationObserver* watcher, TrialOutcome* out) const {
    Chemical chemical;
    chemical.source = sources[k];
    chemical.decay_length = config_.guidance.decay_length;
    chemical.skin_cells = skin;
    GrnBatchT<S> grn = development_.grn();
    MorphogenFieldT<S> field = development_.field();
    SoftBody trial_body = *soft_body_;
    MotionState trial_state = state_;
    // A Bullet world of its own (a fresh world per trial; contacts start
    // without the equilibration's cached manifolds).
    std::unique_ptr<MotionStepper> bullet;
    if (config_.physics.backend == PhysicsBackend::kBullet) {
      bullet = MakeBulletStepper(&trial_body, *body_);
    }
    MotionStepper& stepper = bullet ? *bullet : trial_body;
    if (watcher) watcher->OnGuidanceTrial(k, sources);
    // A knock-out of the chemical (docs/analysis.md): no sensing, so every
    // cell's CHEMICAL reads the 0 it read during development.
    const bool sensing = options_.knockout.kind != Knockout::Kind::kChemical;
    out->motion = RunMotion(config_, grn, field, trial_body, stepper,
                            &trial_state, sensing ? &chemical : nullptr,
                            config_.guidance.lead_steps, watcher);
    if (!out->motion.problem.empty()) return;
    const Vec2 end = CentreOfMass(trial_state);
    out->distance = Length(end - start);
    out->energy = Energy(config_.evaluation, trial_body, out->motion);
    out->source_distance = Length(end - chemical.source);
    StateHash hash;
    HashFinalState(trial_state, grn, &hash);
    out->hash = hash.value();
  }

  // Every guidance trial (model §10.2) on up to options.threads threads,
  // combined in trial order once all have finished, so the result does not
  // depend on the thread count: the first failure decides, and the steps
  // count up to it.
  EvaluationResult GuidanceTrials() {
    const GuidanceParams& g = config_.guidance;
    const int trials = g.trials;
    const Vec2 start = CentreOfMass(state_);
    const std::vector<int> skin = SkinCells(*body_);
    const bool watch_all =
        observer_ && options_.observed_trial == EvaluateOptions::kAllTrials;
    const int observed = observer_ && !watch_all ? options_.observed_trial : -1;
    std::vector<Vec2> sources(trials);
    for (int k = 0; k < trials; ++k) {
      sources[k] = GuidanceSource(start, k, trials, g.source_distance);
    }
    std::vector<TrialOutcome> outcomes(trials);
    const int threads =
        watch_all ? 1 : std::min(std::max(options_.threads, 1), trials);
    // The observed trial runs first, on this thread: the observer is
    // called on the evaluating thread.
    RunEveryTrial(
        trials, threads, observed,
        [&](int k) {
          RunTrial(k, sources, skin, start,
                   watch_all || k == observed ? observer_ : nullptr,
                   &outcomes[k]);
        },
        outcomes);
    StateHash hash;
    Swum swum;
    swum.max_overlap = max_overlap_;
    for (int k = 0; k < trials; ++k) {
      const TrialOutcome& out = outcomes[k];
      progress_.steps += out.motion.steps;
      if (!out.motion.problem.empty()) {
        return Failed(progress_, EvalStatus::kNumericalFailure,
                      "trial " + std::to_string(k) + ": " + out.motion.problem);
      }
      swum.fitness += g.source_distance - out.source_distance;
      swum.distance += out.distance;
      swum.energy += out.energy;
      swum.max_overlap = std::max(swum.max_overlap, out.motion.max_overlap);
      swum.source_distances.push_back(out.source_distance);
      hash.AddU64(out.hash);
    }
    swum.fitness /= trials;
    swum.distance /= trials;
    swum.energy /= trials;
    swum.state_hash = hash.value();
    return Finished(progress_, std::move(swum));
  }

  const Network& network_;
  const ModelConfig& config_;
  const EvaluationParams& ev_;
  EvaluationObserver* observer_;
  const EvaluateOptions& options_;
  DevelopmentT<S> development_;
  Progress progress_;
  std::optional<Body> body_;
  std::optional<SoftBody> soft_body_;
  std::unique_ptr<MotionStepper> bullet_;
  MotionState state_;
  std::vector<double> expand_, contract_;
  double max_overlap_ = 0.0;  // Over equilibration so far.
};

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
    return Failed(Progress{}, EvalStatus::kInvalidGenome, valid.message());
  }
  const Network network = Network::Build(genome, config.grn);
  const Viability viability = network.CheckViability();
  if (!viability.viable) {
    return Failed(Progress{}, EvalStatus::kNonViable, viability.reason);
  }
  if (config.grn.precision == Precision::kFloat) {
    return Pipeline<float>(network, config, observer, options).Run();
  }
  return Pipeline<double>(network, config, observer, options).Run();
}

std::optional<std::string> EvaluationKey(const Genome& genome,
                                         const ModelConfig& config) {
  if (!ValidateGenome(genome).ok()) return std::nullopt;
  return Network::Build(genome, config.grn).Key();
}

}  // namespace animat
