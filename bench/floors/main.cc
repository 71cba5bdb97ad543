// animat-floors: how far each part of an evaluation is from what its
// arithmetic needs on this machine (docs/benchmarks.md, "Floors").
//
//   build/bin/animat-floors [--genome FILE]
//
// For the reference workload (bench/data/bench-genome.json, the default
// configuration) it counts the arithmetic each component must do (the
// model's operations, from the body and the network that develop), prices
// it at this machine's measured cost per lane on its widest vector path
// (floors/primitives.h), and sets that floor beside the component's
// measured time. A floor assumes every operation fully vectorised, no
// loads, stores, gathers or dependencies: it bounds from below what any
// implementation of the same operations in the same precision could take.
//
// Exit 0 once the table is printed, 1 when --genome is not a genome, 2 on
// a usage error.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "bench/floors/primitives.h"
#include "common/body/body.h"
#include "common/command_line/command_line.h"
#include "common/development/development.h"
#include "common/evaluation/evaluator.h"
#include "common/genome/genome_proto.h"
#include "common/io/proto_file.h"
#include "common/kernels/isa.h"
#include "common/physics/soft_body.h"

namespace animat::floors {
namespace {

using Clock = std::chrono::steady_clock;

// Best of `runs` timings of fn(), in milliseconds per call.
template <typename Fn>
double BestMs(Fn fn, int calls, int runs = 7) {
  double best = 1e300;
  for (int r = 0; r < runs; ++r) {
    const auto start = Clock::now();
    for (int c = 0; c < calls; ++c) fn();
    best = std::min(
        best, std::chrono::duration<double, std::milli>(Clock::now() - start)
                      .count() /
                  calls);
  }
  return best;
}

// Full force evaluations an integrator needs per sub-step (docs/model.md
// §7.6), at the least.
double ForceEvaluationsPerSubstep(Integrator integrator) {
  switch (integrator) {
    case Integrator::kSemiImplicitEuler:
    case Integrator::kVelocityVerlet:
      return 1;
    case Integrator::kSsprk3:
    case Integrator::kRalston3:
      return 3;
    case Integrator::kRk4:
      return 4;
  }
  return 1;
}

// The work of one network update: weights applied per cell (those from
// sources other than the inputs frozen in motion: every input but
// CHEMICAL, which is read at every step) and levels updated.
struct NetworkWork {
  long weights = 0;
  long targets = 0;
};

NetworkWork CountNetwork(const Network& net, const std::vector<bool>& needed,
                         bool frozen_inputs) {
  NetworkWork w;
  for (int t : net.targets()) w.targets += needed[t] ? 1 : 0;
  for (size_t s = 0; s < net.sources().size(); ++s) {
    if (frozen_inputs &&
        static_cast<int>(s) < net.static_input_source_count()) {
      continue;
    }
    if (!needed[net.sources()[s].node]) continue;
    for (int k = net.row_begin()[s]; k < net.row_begin()[s + 1]; ++k) {
      w.weights += needed[net.targets()[net.weight_target()[k]]] ? 1 : 0;
    }
  }
  return w;
}

// Floating-point additions and multiplications, divisions and square
// roots, in double, of one force evaluation (docs/model.md §7), counted
// from the formulas: a spring 21 flops, a division for each of its unit
// vector's two components, a square root; a chamber's shoelace 6 per
// vertex after the first two and 3 more for its pressure factor, with one
// division; a pressure push 8 per walk step; a skin edge's drag 40, two
// divisions, a square root.
struct PhysicsWork {
  double flops = 0, divisions = 0, roots = 0;
};

PhysicsWork CountForces(const Body& body) {
  PhysicsWork w;
  const double springs = static_cast<double>(body.springs.size());
  const double skin = static_cast<double>(body.skin.size());
  w.flops = 21 * springs + 40 * skin;
  w.divisions = 2 * springs + 2 * skin;
  w.roots = springs + skin;
  for (const Chamber& c : body.chambers) {
    const double len = static_cast<double>(c.walk.size());
    w.flops += 6 * (len - 2) + 3 + 8 * len;
    w.divisions += 1;
  }
  return w;
}

struct Row {
  std::string component, work;
  double floor_ms = 0, now_ms = 0;
};

int Run(const std::string& genome_path) {
  v1::Genome message;
  Status read = ReadProtoFile(genome_path, &message);
  Result<Genome> genome =
      read.ok() ? GenomeFromProto(message) : Result<Genome>(read);
  if (!genome.ok()) {
    std::fprintf(stderr, "animat-floors: %s\n",
                 genome.status().ToString().c_str());
    return 1;
  }
  const ModelConfig config;
  const PrimitiveCosts cost = MeasurePrimitives();
  const double flop_double = 0.5 * std::min(cost.add_double, cost.mul_double);
  const double flop_float = 0.5 * std::min(cost.add_float, cost.mul_float);

  // Development, watched step by step for its pair counts.
  const Network network = Network::Build(*genome, config.grn);
  constexpr OutputChannel kMotion[] = {OutputChannel::kExpand,
                                       OutputChannel::kContract};
  const std::vector<bool> dev_needed =
      network.NodesReaching(kAllOutputChannels);
  const NetworkWork dev_net = CountNetwork(network, dev_needed, false);
  int dev_morphogens = 0;
  for (int node : network.morphogen_nodes()) {
    dev_morphogens += dev_needed[node] ? 1 : 0;
  }
  double dev_floor_ns = 0, dev_pairs = 0, dev_near_pairs = 0;
  const int substeps = config.development.mechanics_substeps;
  const double range = config.development.interaction_range;
  DevelopmentT<float> watched(network, config.grn, config.development,
                              config.signals);
  watched.Run([&](int, const DevelopmentT<float>& d) {
    const Embryo& e = d.embryo();
    const double c = e.cells();
    const double pairs = c * (c - 1) / 2;
    double near = 0;
    for (int i = 0; i < e.cells(); ++i) {
      for (int j = i + 1; j < e.cells(); ++j) {
        near += Length(e.position[j] - e.position[i]) <
                        range * (e.radius[i] + e.radius[j])
                    ? 1
                    : 0;
      }
    }
    dev_pairs += pairs;
    dev_near_pairs += near;
    // Geometry: each pair's distance (5 flops, a root) and its kernel;
    // signals: every pair per morphogen (2 flops); the network; the
    // mechanics' near pairs per sub-step (13 flops, a root, a division).
    dev_floor_ns +=
        pairs * (5 * flop_double + cost.sqrt_double + cost.pair_kernel_double);
    dev_floor_ns += c * c * dev_morphogens * 2 * flop_float;
    dev_floor_ns += c * (dev_net.weights * 2 * flop_float +
                         dev_net.targets * cost.level_update_float);
    dev_floor_ns += substeps * near *
                    (13 * flop_double + cost.sqrt_double + cost.div_double);
  });

  // The developed body and the motion phase's network, as the evaluator
  // prepares them.
  DevelopmentT<float> development(network, config.grn, config.development,
                                  config.signals);
  development.Run();
  const Embryo& embryo = development.embryo();
  Result<Body> body = BuildBody(embryo.position, embryo.radius);
  if (!body.ok()) {
    std::fprintf(stderr, "animat-floors: the genome develops no body\n");
    return 1;
  }
  const std::vector<bool> motion_needed = network.NodesReaching(kMotion);
  development.RestrictTo(motion_needed);
  GrnBatchT<float>& grn = development.grn();
  for (int cell = 0; cell < grn.cells(); ++cell) {
    grn.SetInputs(
        cell, InputValuesAt(embryo.position[cell],
                            development.maternal_sources(), config.signals));
  }
  grn.FreezeInputs();
  MorphogenFieldT<float>& field = development.field();
  field.SetGeometry(embryo.position);
  const NetworkWork motion_net = CountNetwork(network, motion_needed, true);
  const double cells = embryo.cells();
  const int motion_morphogens = field.morphogens();

  // Floors per step, in nanoseconds.
  const PhysicsWork forces = CountForces(*body);
  // Force evaluations per step: the configured integrator's per sub-step
  // (velocity Verlet's forces at a sub-step's end serve its next start
  // where they depend on positions only, so one at least), times its
  // sub-steps.
  const double stages = ForceEvaluationsPerSubstep(config.physics.integrator) *
                        config.physics.substeps;
  const double nodes = body->nodes();
  // Per node and evaluation: its stage's update of position and velocity
  // (8 flops in two coordinates); per spring and step: its rest length
  // from the actuation (7).
  const double physics_flops =
      stages * (forces.flops + 8 * nodes) + 7 * body->springs.size();
  const double physics_ns =
      std::max(physics_flops * flop_double,
               stages * (forces.divisions * cost.div_double +
                         forces.roots * cost.sqrt_double));
  const double network_ns =
      cells * (motion_net.weights * 2 * flop_float +
               motion_net.targets * cost.level_update_float);
  const double signals_ns = cells * cells * motion_morphogens * 2 * flop_float;
  const int motion_steps = config.evaluation.motion_steps;
  const int equilibration_steps = config.evaluation.equilibration_steps;
  const double steps = motion_steps + equilibration_steps;

  // Measured.
  SoftBody soft_body(*body, config.physics);
  soft_body.SetActuation(std::vector<double>(body->nodes(), 0.3),
                         std::vector<double>(body->nodes(), 0.1));
  MotionState state{body->position, std::vector<Vec2>(body->nodes(), Vec2{})};
  const double physics_now = BestMs([&] { soft_body.Step(&state); }, 2000);
  const double network_now = BestMs([&] { grn.Step(); }, 2000);
  int step = config.development.steps;
  const double signals_now = BestMs(
      [&] {
        field.Record(step, grn);
        field.Apply(step, &grn);
        ++step;
      },
      2000);
  const double development_now = BestMs(
      [&] {
        DevelopmentT<float> d(network, config.grn, config.development,
                              config.signals);
        d.Run();
      },
      20);
  const double evaluation_now =
      BestMs([&] { (void)Evaluate(*genome, config); }, 3, 5);

  std::vector<Row> rows;
  char work[160];
  std::snprintf(work, sizeof(work),
                "%.0f steps x %.0f force evaluations (%s x%d): %.0f flops, "
                "%.0f divisions, %.0f roots each",
                steps, stages, IntegratorName(config.physics.integrator),
                config.physics.substeps, forces.flops, forces.divisions,
                forces.roots);
  rows.push_back(
      {"physics", work, physics_ns * steps * 1e-6, physics_now * steps});
  std::snprintf(work, sizeof(work),
                "%d steps x %.0f cells x (%ld weights, %ld level updates)",
                motion_steps, cells, motion_net.weights, motion_net.targets);
  rows.push_back({"network", work, network_ns * motion_steps * 1e-6,
                  network_now * motion_steps});
  std::snprintf(work, sizeof(work),
                "%d steps x %.0f x %.0f cell pairs x %d morphogens",
                motion_steps, cells, cells, motion_morphogens);
  rows.push_back({"signals", work, signals_ns * motion_steps * 1e-6,
                  signals_now * motion_steps});
  std::snprintf(work, sizeof(work),
                "%d steps: %.0f cell pairs (geometry, signals), %.0f near "
                "pairs (mechanics)",
                config.development.steps, dev_pairs, dev_near_pairs);
  rows.push_back({"development", work, dev_floor_ns * 1e-6, development_now});
  double floor_sum = 0, now_sum = 0;
  for (const Row& r : rows) {
    floor_sum += r.floor_ms;
    now_sum += r.now_ms;
  }

  std::printf(
      "Floors on this machine's widest path (%s: %d doubles, %d floats a "
      "vector), per lane: add %.4f ns, mul %.4f ns, div %.4f ns, sqrt %.4f "
      "ns (double); add %.4f ns, mul %.4f ns, div %.4f ns (float); the "
      "network's level update (tanh, float) %.3f ns; the signals' pair "
      "kernel (exp, double) %.3f ns. Instruction-set path in use: %s.\n\n",
      cost.path.c_str(), cost.double_lanes, cost.float_lanes, cost.add_double,
      cost.mul_double, cost.div_double, cost.sqrt_double, cost.add_float,
      cost.mul_float, cost.div_float, cost.level_update_float,
      cost.pair_kernel_double, IsaReport().c_str());
  std::printf(
      "| component | work per evaluation | floor ms | now ms | now / "
      "floor |\n|---|---|---:|---:|---:|\n");
  for (const Row& r : rows) {
    std::printf("| %s | %s | %.2f | %.2f | %.1f |\n", r.component.c_str(),
                r.work.c_str(), r.floor_ms, r.now_ms, r.now_ms / r.floor_ms);
  }
  std::printf("| sum of the parts | | %.2f | %.2f | %.1f |\n", floor_sum,
              now_sum, now_sum / floor_sum);
  std::printf("| whole evaluation (`Evaluate`) | | | %.2f | |\n",
              evaluation_now);
  return 0;
}

}  // namespace
}  // namespace animat::floors

int main(int argc, char** argv) {
  CLI::App app{
      "animat-floors: each part of an evaluation against what its "
      "arithmetic needs on this machine (docs/benchmarks.md)"};
  std::string genome =
      std::string(ANIMAT_BENCH_DATA_DIR) + "/bench-genome.json";
  app.add_option("--genome", genome, "The workload's genome")
      ->capture_default_str();
  if (const std::optional<int> code =
          animat::ParseCommandLine(app, argc, argv, "animat-floors")) {
    return *code;
  }
  return animat::floors::Run(genome);
}
