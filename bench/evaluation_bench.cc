// Cost of one evaluation and of its parts, for the reference workload: a
// 32-cell animat with a 20-node network (bench/data/bench-genome.json).
//
//   build/bin/animat-bench [--benchmark_filter=...]
//
// BM_Evaluate reports ms per full evaluation (6600 steps); the per-step
// benchmarks report us per simulation step of the motion phase: physics
// (BM_PhysicsStep), and the network side (BM_GrnStep) split into its
// network update (BM_NetworkStep) and morphogen signals (BM_SignalStep).
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "common/body/body.h"
#include "common/development/development.h"
#include "common/development/signals.h"
#include "common/evaluation/evaluator.h"
#include "common/genome/genome_proto.h"
#include "common/io/proto_file.h"
#include "common/physics/soft_body.h"

namespace animat {
namespace {

const Genome& BenchGenome() {
  static const Genome genome = [] {
    const std::string path =
        std::string(ANIMAT_BENCH_DATA_DIR) + "/bench-genome.json";
    v1::Genome message;
    Status status = ReadProtoFile(path, &message);
    Result<Genome> genome =
        status.ok() ? GenomeFromProto(message) : Result<Genome>(status);
    if (!genome.ok()) {
      std::fprintf(stderr, "%s\n", genome.status().ToString().c_str());
      std::exit(1);
    }
    return *genome;
  }();
  return genome;
}

// The reference workload after development, ready for motion steps.
struct Developed {
  ModelConfig config;
  Network network;
  Development development;
  Body body;
  explicit Developed(const Genome& genome)
      : network(Network::Build(genome, config.grn)),
        development(network, config.grn, config.development, config.signals) {
    development.Run();
    body = *BuildBody(development.embryo().position);
    GrnBatch& grn = development.grn();
    for (int cell = 0; cell < grn.cells(); ++cell) {
      grn.SetInputs(
          cell, InputValuesAt(development.embryo().position[cell],
                              development.maternal_sources(), config.signals));
    }
    grn.FreezeInputs();
    development.field().SetGeometry(development.embryo().position);
  }
};

// state.range(0): 0 double, 1 float network arithmetic.
void BM_Evaluate(benchmark::State& state) {
  const Genome& genome = BenchGenome();
  ModelConfig config;
  if (state.range(0) == 1) config.grn.precision = Precision::kFloat;
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
    ->ArgName("float")
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond);

void BM_Development(benchmark::State& state) {
  const Genome& genome = BenchGenome();
  const ModelConfig config;
  const Network network = Network::Build(genome, config.grn);
  for (auto _ : state) {
    Development development(network, config.grn, config.development,
                            config.signals);
    benchmark::DoNotOptimize(development.Run());
  }
}
BENCHMARK(BM_Development)->Unit(benchmark::kMillisecond);

void BM_PhysicsStep(benchmark::State& state) {
  Developed d(BenchGenome());
  SoftBody body(d.body, d.config.physics);
  std::vector<double> expand(d.body.nodes(), 0.3), contract(d.body.nodes());
  body.SetActuation(expand, contract);
  MotionState motion{d.body.position,
                     std::vector<Vec2>(d.body.nodes(), Vec2{})};
  for (auto _ : state) {
    body.Step(&motion);
    benchmark::DoNotOptimize(motion.position.data());
  }
  state.counters["springs"] = d.body.springs.size();
  state.counters["chambers"] = d.body.chambers.size();
  state.counters["skin"] = d.body.skin.size();
}
BENCHMARK(BM_PhysicsStep)->Unit(benchmark::kMicrosecond);

void BM_NetworkStep(benchmark::State& state) {
  Developed d(BenchGenome());
  GrnBatch& grn = d.development.grn();
  for (auto _ : state) grn.Step();
  state.counters["nodes"] = d.network.node_count();
  state.counters["weights"] = d.network.weight_value().size();
}
BENCHMARK(BM_NetworkStep)->Unit(benchmark::kMicrosecond);

// One motion step of the whole network side: signals, then network.
void BM_GrnStep(benchmark::State& state) {
  Developed d(BenchGenome());
  GrnBatch& grn = d.development.grn();
  MorphogenField& field = d.development.field();
  int step = d.config.development.steps;
  for (auto _ : state) {
    field.Record(step, grn);
    field.Apply(step, &grn);
    grn.Step();
    ++step;
  }
  state.counters["nodes"] = d.network.node_count();
  state.counters["morphogens"] = field.morphogens();
}
BENCHMARK(BM_GrnStep)->Unit(benchmark::kMicrosecond);

void BM_SignalStep(benchmark::State& state) {
  Developed d(BenchGenome());
  GrnBatch& grn = d.development.grn();
  MorphogenField& field = d.development.field();
  int step = d.config.development.steps;
  for (auto _ : state) {
    field.Record(step, grn);
    field.Apply(step, &grn);
    ++step;
  }
  state.counters["morphogens"] = field.morphogens();
}
BENCHMARK(BM_SignalStep)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace animat

BENCHMARK_MAIN();
