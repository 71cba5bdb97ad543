#include "common/evaluation/knockout.h"

#include <algorithm>
#include <atomic>
#include <system_error>
#include <thread>

namespace animat {
namespace {

constexpr OutputChannel kActuators[] = {OutputChannel::kExpand,
                                        OutputChannel::kContract};

// Runs job(i) for i in [0, count) on up to `threads` threads.
template <typename Job>
void RunAll(int count, int threads, const Job& job) {
  std::atomic<int> next{0};
  auto work = [&] {
    for (int i = next.fetch_add(1); i < count; i = next.fetch_add(1)) job(i);
  };
  std::vector<std::thread> helpers;
  try {
    for (int t = 1; t < std::min(threads, count); ++t) {
      helpers.emplace_back(work);
    }
  } catch (const std::system_error&) {
    // No more threads: the ones started and this one share the work.
  }
  work();
  for (std::thread& helper : helpers) helper.join();
}

v1::Knockout RunToProto(const KnockoutRun& run) {
  v1::Knockout m;
  switch (run.knockout.kind) {
    case Knockout::Kind::kNone:
      m.set_kind(v1::Knockout::NONE);
      break;
    case Knockout::Kind::kChemical:
      m.set_kind(v1::Knockout::CHEMICAL);
      m.set_actuator_path(run.actuator_path);
      break;
    case Knockout::Kind::kMorphogen:
      m.set_kind(v1::Knockout::MORPHOGEN);
      m.set_node(run.knockout.node);
      m.set_unit_element(run.unit_element);
      m.set_chemical_path(run.chemical_path);
      m.set_actuator_path(run.actuator_path);
      break;
  }
  *m.mutable_result() = EvaluationResultToProto(run.result);
  if (run.fitness_change) m.set_fitness_change(*run.fitness_change);
  return m;
}

}  // namespace

std::vector<int> MotionMorphogenUnits(const Network& network) {
  const std::vector<bool> needed = network.NodesReaching(kActuators);
  std::vector<int> units;
  for (int node : network.morphogen_nodes()) {
    if (needed[node]) units.push_back(node);
  }
  return units;
}

bool ChemicalReaches(const Network& network, int node) {
  std::vector<bool> seen(network.node_count(), false);
  std::vector<int> frontier =
      network.input_nodes(static_cast<int>(InputChannel::kChemical));
  for (int s : frontier) seen[s] = true;
  while (!frontier.empty()) {
    const int s = frontier.back();
    frontier.pop_back();
    if (s == node) return true;
    for (int u : network.successors()[s]) {
      if (!seen[u]) {
        seen[u] = true;
        frontier.push_back(u);
      }
    }
  }
  return false;
}

bool MorphogenReachesActuators(const Genome& genome, const Network& network,
                               const GrnParams& params, int node) {
  const std::vector<bool> needed = network.NodesReaching(kActuators);
  for (int f : network.nodes()[node].factors) {
    const Element& factor = genome.elements[f];
    if (factor.type != ElementType::kGMorphogen) continue;
    for (int u = 0; u < network.node_count(); ++u) {
      if (!needed[u]) continue;
      for (int r : network.nodes()[u].regions) {
        if (Binds(factor, genome.elements[r], params)) return true;
      }
    }
  }
  return false;
}

KnockoutReport RunKnockouts(const Genome& genome, const ModelConfig& config,
                            int threads) {
  KnockoutReport report;
  report.guidance = config.guidance.enabled;
  std::vector<KnockoutRun> runs;
  if (ValidateGenome(genome).ok()) {
    const Network network = Network::Build(genome, config.grn);
    if (report.guidance) {
      KnockoutRun run;
      run.knockout.kind = Knockout::Kind::kChemical;
      run.chemical_path = true;
      const std::vector<bool> needed = network.NodesReaching(kActuators);
      for (int node :
           network.input_nodes(static_cast<int>(InputChannel::kChemical))) {
        if (needed[node]) run.actuator_path = true;
      }
      runs.push_back(run);
    }
    for (int node : MotionMorphogenUnits(network)) {
      KnockoutRun run;
      run.knockout.kind = Knockout::Kind::kMorphogen;
      run.knockout.node = node;
      run.unit_element = network.nodes()[node].first_element;
      run.chemical_path = ChemicalReaches(network, node);
      run.actuator_path =
          MorphogenReachesActuators(genome, network, config.grn, node);
      runs.push_back(run);
    }
  }

  // Evaluation 0 is the intact one, evaluation i > 0 is runs[i - 1].
  const int count = 1 + static_cast<int>(runs.size());
  RunAll(count, std::max(threads, 1), [&](int i) {
    EvaluateOptions options;
    if (i > 0) options.knockout = runs[i - 1].knockout;
    EvaluationResult result = Evaluate(genome, config, nullptr, options);
    if (i == 0) {
      report.intact = std::move(result);
    } else {
      runs[i - 1].result = std::move(result);
    }
  });
  for (KnockoutRun& run : runs) {
    if (report.intact.fitness && run.result.fitness) {
      run.fitness_change = *run.result.fitness - *report.intact.fitness;
    }
  }
  report.runs = std::move(runs);
  return report;
}

v1::KnockoutAnalysis KnockoutReportToProto(const KnockoutReport& report) {
  v1::KnockoutAnalysis m;
  m.set_guidance(report.guidance);
  KnockoutRun intact;
  intact.result = report.intact;
  *m.mutable_intact() = RunToProto(intact);
  for (const KnockoutRun& run : report.runs) {
    *m.add_knockout() = RunToProto(run);
  }
  return m;
}

}  // namespace animat
