// Cost of one evaluation and of each of its parts, for the reference
// workload: a 32-cell animat with a 20-node network
// (bench/data/bench-genome.json).
//
//   build/bin/animat-bench [--benchmark_filter=...]
//
// BM_Evaluate reports ms per full evaluation (6600 steps), with double and
// float network arithmetic, on every instruction-set path of the kernels
// (common/kernels/isa.h; a path the machine lacks is skipped);
// BM_EvaluateIntegrator the same under each integrator. BM_EvaluateFailure
// is the cost of an evaluation that fails: a non-viable network, too few
// cells, a body without a chamber, a late division (bench/data/failing/,
// and the reference genome with divisions required to end by step 10). The
// per-step benchmarks report us per simulation step of the motion phase, set up
// as the evaluator sets it up (only nodes that influence EXPAND or CONTRACT,
// inputs frozen): physics (BM_PhysicsStep, per integrator; each force family
// alone; the Bullet backend with and without contacts), and the network side
// (BM_GrnStep) split into its network update (BM_NetworkStep) and morphogen
// signals (BM_SignalStep), each in double and float.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "common/body/body.h"
#include "common/development/development.h"
#include "common/development/signals.h"
#include "common/evaluation/evaluator.h"
#include "common/genome/genome_proto.h"
#include "common/io/proto_file.h"
#include "common/kernels/isa.h"
#include "common/physics/bullet/bullet_stepper.h"
#include "common/physics/soft_body.h"

namespace animat {
namespace {

// A genome of bench/data; exits with the reason if it cannot be read.
Genome LoadBenchGenome(const std::string& name) {
  const std::string path = std::string(ANIMAT_BENCH_DATA_DIR) + "/" + name;
  v1::Genome message;
  Status status = ReadProtoFile(path, &message);
  Result<Genome> genome =
      status.ok() ? GenomeFromProto(message) : Result<Genome>(status);
  if (!genome.ok()) {
    std::fprintf(stderr, "%s\n", genome.status().ToString().c_str());
    std::exit(1);
  }
  return *genome;
}

const Genome& BenchGenome() {
  static const Genome genome = LoadBenchGenome("bench-genome.json");
  return genome;
}

// The reference workload after development, ready for motion steps as the
// evaluator prepares them.
template <typename S>
struct Developed {
  ModelConfig config;
  Network network;
  DevelopmentT<S> development;
  Body body;
  explicit Developed(const Genome& genome)
      : network(Network::Build(genome, config.grn)),
        development(network, config.grn, config.development, config.signals) {
    development.Run();
    const Embryo& embryo = development.embryo();
    body = *BuildBody(embryo.position, embryo.radius);
    constexpr OutputChannel kMotion[] = {OutputChannel::kExpand,
                                         OutputChannel::kContract};
    development.RestrictTo(network.NodesReaching(kMotion));
    GrnBatchT<S>& grn = development.grn();
    for (int cell = 0; cell < grn.cells(); ++cell) {
      grn.SetInputs(
          cell, InputValuesAt(embryo.position[cell],
                              development.maternal_sources(), config.signals));
    }
    grn.FreezeInputs();
    development.field().SetGeometry(embryo.position);
  }
};

// Runs the benchmark on instruction-set path `isa` (common/kernels/isa.h),
// restoring the path in use afterwards; skips a path this machine lacks.
class OnPath {
 public:
  OnPath(benchmark::State& state, int64_t isa) : saved_(ActiveIsa()) {
    const Isa path = static_cast<Isa>(isa);
    ok_ = SelectIsa(path).ok();
    if (!ok_) {
      state.SkipWithError(
          (std::string(IsaName(path)) + " not supported").c_str());
    } else {
      state.SetLabel(IsaName(path));
    }
  }
  ~OnPath() { (void)SelectIsa(saved_); }
  bool ok() const { return ok_; }

 private:
  Isa saved_;
  bool ok_ = false;
};

// Every instruction-set path: 0 baseline, 1 AVX2, 2 AVX-512.
void EveryPath(benchmark::internal::Benchmark* b, const char* first_name,
               std::initializer_list<int64_t> firsts) {
  b->ArgNames({first_name, "isa"});
  for (int64_t first : firsts) {
    for (int64_t isa : {0, 1, 2}) b->Args({first, isa});
  }
}

// state.range(0): 0 double, 1 float network arithmetic; state.range(1):
// the instruction-set path. The default configuration (Ralston's third
// order, one sub-step).
void BM_Evaluate(benchmark::State& state) {
  OnPath path(state, state.range(1));
  if (!path.ok()) return;
  const Genome& genome = BenchGenome();
  ModelConfig config;
  config.grn.precision =
      state.range(0) == 1 ? Precision::kFloat : Precision::kDouble;
  EvaluationResult result;
  for (auto _ : state) {
    result = Evaluate(genome, config);
    benchmark::DoNotOptimize(result);
  }
  state.counters["cells"] = result.cells;
  state.counters["nodes"] = Network::Build(genome, config.grn).node_count();
  state.counters["ok"] = result.status == EvalStatus::kOk;
}
BENCHMARK(BM_Evaluate)
    ->Apply([](benchmark::internal::Benchmark* b) {
      EveryPath(b, "float", {0, 1});
    })
    ->Unit(benchmark::kMillisecond);

// The default evaluation on one and on two threads of one process at
// once, as a worker with --threads 2 runs them: the wall time of an
// evaluation as each thread sees it, and evaluations per second over all
// threads (items_per_second). Against two single-threaded processes
// (animat-dispatch-bench), this isolates what two threads of one process
// share.
void BM_EvaluateThreads(benchmark::State& state) {
  const Genome& genome = BenchGenome();
  ModelConfig config;
  config.grn.precision = Precision::kFloat;
  EvaluationResult result;
  for (auto _ : state) {
    result = Evaluate(genome, config);
    benchmark::DoNotOptimize(result);
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["ok"] = result.status == EvalStatus::kOk;
}
BENCHMARK(BM_EvaluateThreads)
    ->Threads(1)
    ->Threads(2)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// The default configuration with another integrator and one sub-step
// (float network, the path in use): state.range(0) is the Integrator (0
// semi-implicit Euler, the default before model v2; 2 RK4, the first
// default under v2; 4 Ralston's, v2's last).
void BM_EvaluateIntegrator(benchmark::State& state) {
  const Genome& genome = BenchGenome();
  ModelConfig config;
  config.physics.integrator = static_cast<Integrator>(state.range(0));
  config.physics.substeps = 1;
  EvaluationResult result;
  for (auto _ : state) {
    result = Evaluate(genome, config);
    benchmark::DoNotOptimize(result);
  }
  state.SetLabel(IntegratorName(config.physics.integrator));
  state.counters["ok"] = result.status == EvalStatus::kOk;
}
BENCHMARK(BM_EvaluateIntegrator)
    ->DenseRange(0, 4)
    ->Unit(benchmark::kMillisecond);

// state.range(0): the contact rule, 0 NONE, 1 UNJOINED, 2 ALL.
ContactRule RuleArg(int64_t arg) {
  return arg == 0   ? ContactRule::kNone
         : arg == 1 ? ContactRule::kUnjoined
                    : ContactRule::kAll;
}

// The default evaluation under each contact rule (model §7.10): what
// contacts cost.
void BM_EvaluateContacts(benchmark::State& state) {
  const Genome& genome = BenchGenome();
  ModelConfig config;
  config.physics.contact_rule = RuleArg(state.range(0));
  EvaluationResult result;
  for (auto _ : state) {
    result = Evaluate(genome, config);
    benchmark::DoNotOptimize(result);
  }
  state.SetLabel(ContactRuleName(config.physics.contact_rule));
  state.counters["ok"] = result.status == EvalStatus::kOk;
}
BENCHMARK(BM_EvaluateContacts)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);

// The Bullet backend (the anchor the native integrators are measured
// against): the same forces integrated by a Bullet world, without
// (state.range(0) == 0) or with cell-cell contacts between every pair (1,
// model v2's "contacts") or unjoined pairs only (2).
ContactRule BulletRuleArg(int64_t arg) {
  return arg == 0   ? ContactRule::kNone
         : arg == 1 ? ContactRule::kAll
                    : ContactRule::kUnjoined;
}

void BM_EvaluateBullet(benchmark::State& state) {
  const Genome& genome = BenchGenome();
  ModelConfig config;
  config.physics.backend = PhysicsBackend::kBullet;
  config.physics.integrator = Integrator::kSemiImplicitEuler;
  config.physics.contact_rule = BulletRuleArg(state.range(0));
  EvaluationResult result;
  for (auto _ : state) {
    result = Evaluate(genome, config);
    benchmark::DoNotOptimize(result);
  }
  state.SetLabel(ContactRuleName(config.physics.contact_rule));
  state.counters["ok"] = result.status == EvalStatus::kOk;
}
BENCHMARK(BM_EvaluateBullet)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);

// state.range(0): 0 non-viable, 1 too few cells, 2 no chamber, 3 late
// division. The label is the status the evaluation gave.
void BM_EvaluateFailure(benchmark::State& state) {
  static const char* kGenomes[] = {
      "failing/non-viable.json", "failing/too-few-cells.json",
      "failing/no-chamber.json", "bench-genome.json"};
  const Genome genome = LoadBenchGenome(kGenomes[state.range(0)]);
  ModelConfig config;
  if (state.range(0) == 3) config.development.last_division_step = 10;
  EvaluationResult result;
  for (auto _ : state) {
    result = Evaluate(genome, config);
    benchmark::DoNotOptimize(result);
  }
  state.SetLabel(EvalStatusName(result.status));
  state.counters["steps"] = static_cast<double>(result.steps);
}
BENCHMARK(BM_EvaluateFailure)->DenseRange(0, 3)->Unit(benchmark::kMicrosecond);

template <typename S>
void BM_Development(benchmark::State& state) {
  OnPath path(state, state.range(0));
  if (!path.ok()) return;
  const Genome& genome = BenchGenome();
  const ModelConfig config;
  const Network network = Network::Build(genome, config.grn);
  for (auto _ : state) {
    DevelopmentT<S> development(network, config.grn, config.development,
                                config.signals);
    benchmark::DoNotOptimize(development.Run());
  }
}
BENCHMARK_TEMPLATE(BM_Development, double)
    ->ArgName("isa")
    ->DenseRange(0, 2)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_Development, float)
    ->ArgName("isa")
    ->DenseRange(0, 2)
    ->Unit(benchmark::kMillisecond);

// A body of the reference workload with mid-range actuation.
struct PhysicsSetup {
  Developed<double> d{BenchGenome()};
  std::vector<double> expand = std::vector<double>(d.body.nodes(), 0.3);
  std::vector<double> contract = std::vector<double>(d.body.nodes(), 0.1);
  MotionState Start() const {
    return {d.body.position, std::vector<Vec2>(d.body.nodes(), Vec2{})};
  }
};

// state.range(0): 0 semi-implicit Euler, 1 velocity Verlet, 2 RK4, 3 SSPRK3,
// 4 Ralston's third order.
void BM_PhysicsStep(benchmark::State& state) {
  PhysicsSetup setup;
  PhysicsParams params;
  params.integrator = static_cast<Integrator>(state.range(0));
  params.substeps = 1;
  SoftBody body(setup.d.body, params);
  body.SetActuation(setup.expand, setup.contract);
  MotionState motion = setup.Start();
  for (auto _ : state) {
    body.Step(&motion);
    benchmark::DoNotOptimize(motion.position.data());
  }
  state.SetLabel(IntegratorName(params.integrator));
  state.counters["springs"] = setup.d.body.springs.size();
  state.counters["chambers"] = setup.d.body.chambers.size();
  state.counters["skin"] = setup.d.body.skin.size();
}
BENCHMARK(BM_PhysicsStep)->DenseRange(0, 4)->Unit(benchmark::kMicrosecond);

// The default physics step (model §7: velocity Verlet ×4, contacts between
// unjoined cells), with the deepest unjoined overlap measured after it as
// every evaluation does (model §8.6).
void BM_PhysicsStepDefault(benchmark::State& state) {
  PhysicsSetup setup;
  SoftBody body(setup.d.body, PhysicsParams{});
  body.SetActuation(setup.expand, setup.contract);
  MotionState motion = setup.Start();
  double deepest = 0.0;
  for (auto _ : state) {
    body.Step(&motion);
    deepest = std::max(deepest, body.DeepestUnjoinedOverlap(motion));
    benchmark::DoNotOptimize(motion.position.data());
  }
  benchmark::DoNotOptimize(deepest);
  state.SetLabel(std::string(IntegratorName(body.params().integrator)) + " x" +
                 std::to_string(body.params().substeps) + ", " +
                 ContactRuleName(body.params().contact_rule));
}
BENCHMARK(BM_PhysicsStepDefault)->Unit(benchmark::kMicrosecond);

// state.range(0): 0 springs, 1 pressure, 2 drag, 3 contacts (UNJOINED),
// alone; 4 the deepest unjoined overlap every step measures (model §8.6).
void BM_PhysicsForces(benchmark::State& state) {
  PhysicsSetup setup;
  SoftBody body(setup.d.body, PhysicsParams{});
  body.SetActuation(setup.expand, setup.contract);
  MotionState motion = setup.Start();
  for (Vec2& v : motion.velocity) v = {0.01, -0.02};
  std::vector<Vec2> force(setup.d.body.nodes());
  const char* const kLabels[] = {"springs", "pressure", "drag", "contacts",
                                 "overlap"};
  state.SetLabel(kLabels[state.range(0)]);
  for (auto _ : state) {
    switch (state.range(0)) {
      case 0:
        body.AddSpringForces(motion, force.data());
        break;
      case 1:
        body.AddPressureForces(motion, force.data());
        break;
      case 2:
        body.AddDragForces(motion, force.data());
        break;
      case 3:
        body.AddContactForces(motion, force.data());
        break;
      default:
        benchmark::DoNotOptimize(body.DeepestUnjoinedOverlap(motion));
        break;
    }
    benchmark::DoNotOptimize(force.data());
  }
}
BENCHMARK(BM_PhysicsForces)->DenseRange(0, 4)->Unit(benchmark::kMicrosecond);

// state.range(0): as BM_EvaluateBullet's.
void BM_BulletStep(benchmark::State& state) {
  PhysicsSetup setup;
  PhysicsParams params;
  params.backend = PhysicsBackend::kBullet;
  params.integrator = Integrator::kSemiImplicitEuler;
  params.contact_rule = BulletRuleArg(state.range(0));
  SoftBody body(setup.d.body, params);
  body.SetActuation(setup.expand, setup.contract);
  std::unique_ptr<MotionStepper> bullet =
      MakeBulletStepper(&body, setup.d.body);
  MotionState motion = setup.Start();
  for (auto _ : state) {
    bullet->Step(&motion);
    benchmark::DoNotOptimize(motion.position.data());
  }
  state.SetLabel(ContactRuleName(params.contact_rule));
}
BENCHMARK(BM_BulletStep)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);

template <typename S>
void BM_NetworkStep(benchmark::State& state) {
  OnPath path(state, state.range(0));
  if (!path.ok()) return;
  Developed<S> d(BenchGenome());
  GrnBatchT<S>& grn = d.development.grn();
  for (auto _ : state) grn.Step();
  state.counters["nodes"] = d.network.node_count();
  state.counters["weights"] = d.network.weight_value().size();
}
BENCHMARK_TEMPLATE(BM_NetworkStep, double)
    ->ArgName("isa")
    ->DenseRange(0, 2)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_TEMPLATE(BM_NetworkStep, float)
    ->ArgName("isa")
    ->DenseRange(0, 2)
    ->Unit(benchmark::kMicrosecond);

template <typename S>
void BM_SignalStep(benchmark::State& state) {
  OnPath path(state, state.range(0));
  if (!path.ok()) return;
  Developed<S> d(BenchGenome());
  GrnBatchT<S>& grn = d.development.grn();
  MorphogenFieldT<S>& field = d.development.field();
  int step = d.config.development.steps;
  for (auto _ : state) {
    field.Record(step, grn);
    field.Apply(step, &grn);
    ++step;
  }
  state.counters["morphogens"] = field.morphogens();
}
BENCHMARK_TEMPLATE(BM_SignalStep, double)
    ->ArgName("isa")
    ->DenseRange(0, 2)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_TEMPLATE(BM_SignalStep, float)
    ->ArgName("isa")
    ->DenseRange(0, 2)
    ->Unit(benchmark::kMicrosecond);

// One motion step of the whole network side: signals, then network.
template <typename S>
void BM_GrnStep(benchmark::State& state) {
  OnPath path(state, state.range(0));
  if (!path.ok()) return;
  Developed<S> d(BenchGenome());
  GrnBatchT<S>& grn = d.development.grn();
  MorphogenFieldT<S>& field = d.development.field();
  int step = d.config.development.steps;
  for (auto _ : state) {
    field.Record(step, grn);
    field.Apply(step, &grn);
    grn.Step();
    ++step;
  }
}
BENCHMARK_TEMPLATE(BM_GrnStep, double)
    ->ArgName("isa")
    ->DenseRange(0, 2)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_TEMPLATE(BM_GrnStep, float)
    ->ArgName("isa")
    ->DenseRange(0, 2)
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace animat

// main: bench/benchmark_main.cc, which checks the command line first.
