#include "bench/accuracy/experiment.h"

#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <thread>

#include "bench/accuracy/animat_set.h"
#include "bench/accuracy/runner.h"
#include "bench/accuracy/stats.h"

namespace animat::accuracy {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

std::string FirstLineWith(const std::string& path, const std::string& key) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(key, 0) == 0) return line;
  }
  return "";
}

std::string LoadAverage() {
  std::ifstream in("/proc/loadavg");
  double one = 0.0;
  if (!(in >> one)) return "?";
  std::ostringstream out;
  out << one;
  return out.str();
}

std::string CpuModel() {
  std::string line = FirstLineWith("/proc/cpuinfo", "model name");
  const size_t colon = line.find(':');
  if (colon == std::string::npos) return "unknown CPU";
  return line.substr(colon + 2);
}

// The same configuration with physics.dt one ulp larger.
ModelConfig NudgeDt(ModelConfig config) {
  config.physics.dt = std::nextafter(config.physics.dt, kInfinity);
  return config;
}

ChaosResult Chaos(const std::string& name, const std::vector<Run>& base,
                  const std::vector<Run>& nudged,
                  const std::vector<Run>& reference) {
  ChaosResult chaos;
  chaos.config = name;
  chaos.animats = static_cast<int>(base.size());
  std::vector<double> fitness;
  for (size_t a = 0; a < base.size(); ++a) {
    if (!base[a].ok() || !nudged[a].ok()) {
      ++chaos.failures;
      fitness.push_back(kInfinity);
      continue;
    }
    fitness.push_back(std::abs(base[a].fitness - nudged[a].fitness) /
                      reference[a].fitness);
  }
  chaos.fitness_median = Median(fitness);
  chaos.fitness_p90 = Percentile90(fitness);
  chaos.fitness_max = Quantile(fitness, 1.0);
  for (int step : kChaosSteps) {
    std::vector<double> divergence;
    for (size_t a = 0; a < base.size(); ++a) {
      divergence.push_back(
          Divergence(base[a], nudged[a], step, reference[a].fitness));
    }
    chaos.steps.push_back(step);
    chaos.median.push_back(Median(divergence));
    chaos.p90.push_back(Percentile90(divergence));
    chaos.max.push_back(Quantile(divergence, 1.0));
  }
  return chaos;
}

// Each animat's configuration: `config` with the animat's model constants.
Result<std::vector<ModelConfig>> PerAnimat(const ModelConfig& config,
                                           const std::vector<Animat>& animats) {
  std::vector<ModelConfig> configs;
  for (const Animat& animat : animats) {
    Result<ModelConfig> c = ForAnimat(config, animat);
    if (!c.ok()) return c.status();
    configs.push_back(*c);
  }
  return configs;
}

}  // namespace

void Summarise(CandidateResult* result) {
  std::vector<double> fitness, trajectory, ms_ok, ms_all, cpu_ok, cpu_all;
  result->failures = 0;
  result->max_overlap = 0.0;
  for (const AnimatResult& a : result->animats) {
    // Errors only against a converged reference; failures and times of
    // every animat.
    if (a.converged) {
      fitness.push_back(a.fitness_error);
      trajectory.push_back(a.trajectory_error);
    }
    ms_all.push_back(a.ms);
    cpu_all.push_back(a.cpu_ms);
    if (a.status == "ok") {
      result->max_overlap = std::max(result->max_overlap, a.max_overlap);
      ms_ok.push_back(a.ms);
      cpu_ok.push_back(a.cpu_ms);
    } else {
      ++result->failures;
    }
  }
  if (result->animats.empty() || fitness.empty()) return;
  result->fitness_error_median = Median(fitness);
  result->fitness_error_p90 = Percentile90(fitness);
  result->trajectory_error_median = Median(trajectory);
  result->trajectory_error_p90 = Percentile90(trajectory);
  result->ms_median = Median(ms_ok.empty() ? ms_all : ms_ok);
  result->cpu_ms_median = Median(cpu_ok.empty() ? cpu_all : cpu_ok);
}

int OrderSwaps(const std::vector<Run>& runs, const std::vector<Run>& reference,
               const std::vector<bool>& converged, int* pairs) {
  int swaps = 0;
  *pairs = 0;
  for (size_t a = 0; a < runs.size(); ++a) {
    for (size_t b = a + 1; b < runs.size(); ++b) {
      if (!runs[a].ok() || !runs[b].ok()) continue;
      if (!converged[a] || !converged[b]) continue;
      ++*pairs;
      const bool ref_less = reference[a].fitness < reference[b].fitness;
      const bool ref_more = reference[a].fitness > reference[b].fitness;
      const bool less = runs[a].fitness < runs[b].fitness;
      const bool more = runs[a].fitness > runs[b].fitness;
      if ((ref_less && more) || (ref_more && less)) ++swaps;
    }
  }
  return swaps;
}

std::string RuleChoice(const std::vector<CandidateResult>& candidates) {
  double cheapest = kInfinity;
  for (const CandidateResult& c : candidates) {
    if (c.MeetsRule() && c.ms_median < cheapest) cheapest = c.ms_median;
  }
  // Among the equally cheap, the smallest 90th-percentile error; the first
  // of equals.
  std::string choice;
  double best_p90 = kInfinity;
  for (const CandidateResult& c : candidates) {
    if (c.MeetsRule() && c.ms_median <= cheapest * (1.0 + kRuleTimeTie) &&
        c.fitness_error_p90 < best_p90) {
      best_p90 = c.fitness_error_p90;
      choice = c.candidate.Label();
    }
  }
  return choice;
}

Result<Report> RunExperiment(const ExperimentOptions& options) {
  const auto clock_start = std::chrono::steady_clock::now();
  auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                         clock_start)
        .count();
  };
  auto say = [&](const std::string& line) {
    if (options.progress) *options.progress << line << std::endl;
  };

  Result<std::vector<Candidate>> candidates =
      SelectCandidates(options.candidates);
  if (!candidates.ok()) return candidates.status();
  if (options.contact_near >= 0.0) {
    for (Candidate& c : *candidates) c.contact_near = options.contact_near;
  }
  // Every configuration at the one k_c (the model's unless asked).
  auto at_stiffness = [&](Candidate c) {
    c.contact_stiffness = options.contact_stiffness;
    return c;
  };
  for (Candidate& c : *candidates) c = at_stiffness(c);
  Result<std::vector<Animat>> loaded = LoadAnimatSet(options.data_dir);
  if (!loaded.ok()) return loaded.status();
  std::vector<Animat> animats = *loaded;
  if (options.max_animats > 0) {
    if (static_cast<int>(animats.size()) > options.max_animats) {
      animats.resize(options.max_animats);
    }
  } else if (options.quick) {
    animats = QuickSubset(animats, kQuickRandom, kQuickEvolved);
  }
  Result<ModelConfig> reference_config =
      CandidateConfig(at_stiffness(ReferenceCandidate()));
  if (!reference_config.ok()) {
    return reference_config.status().WithPrefix("reference configuration");
  }
  Result<ModelConfig> default_config =
      CandidateConfig(at_stiffness(DefaultCandidate()));
  if (!default_config.ok()) {
    return default_config.status().WithPrefix("default configuration");
  }

  Report report;
  report.quick = options.quick;
  report.repeats = std::max(1, options.repeats);
  report.contact_stiffness = reference_config->physics.contact_stiffness;
  report.machine =
      CpuModel() + ", " + std::to_string(std::thread::hardware_concurrency()) +
      " logical CPUs, load average " + LoadAverage() + " at the start";

  // The reference; an animat whose reference fails is left out.
  std::vector<Run> reference;
  std::vector<double> reference_ms;
  {
    std::vector<Animat> kept;
    for (const Animat& animat : animats) {
      Result<ModelConfig> config = ForAnimat(*reference_config, animat);
      if (!config.ok()) return config.status();
      Run run = RunEvaluation(animat.genome, *config);
      if (!run.ok() || !(run.fitness > 0.0)) {
        report.excluded.push_back(animat.name + " (reference: " +
                                  std::string(EvalStatusName(run.status)) +
                                  " " + run.reason + ")");
        continue;
      }
      reference_ms.push_back(run.seconds * 1e3);
      report.animats.push_back(animat.name);
      report.evolved.push_back(animat.evolved);
      report.reference_fitness.push_back(run.fitness);
      report.reference_overlap.push_back(run.max_overlap);
      reference.push_back(std::move(run));
      kept.push_back(animat);
    }
    animats = std::move(kept);
  }
  if (animats.empty()) {
    return Status::Internal("the reference failed on every animat");
  }
  report.reference_ms_median = Median(reference_ms);
  say(std::string("reference: ") + std::to_string(animats.size()) +
      " animats, " + std::to_string(elapsed()) + " s");

  // Has the reference converged? RK4 with twice its sub-steps.
  {
    Candidate check = at_stiffness(ReferenceCandidate());
    check.substeps *= 2;
    Result<ModelConfig> check_config = CandidateConfig(check);
    if (!check_config.ok()) {
      return check_config.status().WithPrefix("convergence check");
    }
    for (size_t a = 0; a < animats.size(); ++a) {
      Result<ModelConfig> config = ForAnimat(*check_config, animats[a]);
      if (!config.ok()) return config.status();
      const Run run = RunEvaluation(animats[a].genome, *config);
      report.check_fitness.push_back(run.ok() ? run.fitness : kInfinity);
      report.converged.push_back(run.ok() &&
                                 std::abs(reference[a].fitness - run.fitness) <=
                                     kConvergenceTolerance * run.fitness);
    }
    say(std::string("convergence check: ") + std::to_string(elapsed()) + " s");
  }

  // Chaos: one ulp of dt.
  {
    std::vector<Run> base, nudged, reference_nudged;
    Result<std::vector<ModelConfig>> defaults =
        PerAnimat(*default_config, animats);
    Result<std::vector<ModelConfig>> references =
        PerAnimat(*reference_config, animats);
    if (!defaults.ok()) return defaults.status();
    if (!references.ok()) return references.status();
    for (size_t a = 0; a < animats.size(); ++a) {
      const Genome& genome = animats[a].genome;
      base.push_back(RunEvaluation(genome, (*defaults)[a]));
      nudged.push_back(RunEvaluation(genome, NudgeDt((*defaults)[a])));
      if (!options.quick) {
        reference_nudged.push_back(
            RunEvaluation(genome, NudgeDt((*references)[a])));
      }
    }
    // Also over the evolved animats alone when the set has both kinds.
    std::vector<size_t> evolved;
    for (size_t a = 0; a < animats.size(); ++a) {
      if (animats[a].evolved) evolved.push_back(a);
    }
    const bool split = !evolved.empty() && evolved.size() < animats.size();
    auto only_evolved = [&](const std::vector<Run>& runs) {
      std::vector<Run> subset;
      for (size_t a : evolved) subset.push_back(runs[a]);
      return subset;
    };
    const std::string default_name =
        std::string("default (") + DefaultCandidate().Label() + ")";
    report.chaos.push_back(Chaos(default_name, base, nudged, reference));
    if (split) {
      report.chaos.push_back(Chaos(default_name + ", evolved only",
                                   only_evolved(base), only_evolved(nudged),
                                   only_evolved(reference)));
    }
    if (!options.quick) {
      report.chaos.push_back(
          Chaos("reference (R16)", reference, reference_nudged, reference));
      if (split) {
        report.chaos.push_back(
            Chaos("reference (R16), evolved only", only_evolved(reference),
                  only_evolved(reference_nudged), only_evolved(reference)));
      }
    }
    say(std::string("chaos: ") + std::to_string(elapsed()) + " s");
  }

  // Candidates.
  std::vector<CandidateResult> results;
  std::vector<std::vector<ModelConfig>> configs;  // [candidate][animat]
  std::vector<int> loaded_index;                  // Into results.
  for (const Candidate& candidate : *candidates) {
    CandidateResult result;
    result.candidate = candidate;
    Result<ModelConfig> config = CandidateConfig(candidate);
    Result<std::vector<ModelConfig>> per_animat =
        config.ok() ? PerAnimat(*config, animats)
                    : Result<std::vector<ModelConfig>>(config.status());
    if (per_animat.ok()) {
      loaded_index.push_back(static_cast<int>(results.size()));
      configs.push_back(*per_animat);
    } else {
      result.error = per_animat.status().message();
    }
    results.push_back(std::move(result));
  }

  // runs[c][a]: the first repetition; seconds[c][a]: every repetition.
  const size_t n = loaded_index.size();
  std::vector<std::vector<Run>> runs(n, std::vector<Run>(animats.size()));
  std::vector<std::vector<std::vector<double>>> seconds(
      n, std::vector<std::vector<double>>(animats.size()));
  std::vector<std::vector<std::vector<double>>> cpu_seconds = seconds;
  std::vector<std::vector<bool>> deterministic(
      n, std::vector<bool>(animats.size(), true));
  for (int rep = 0; rep < report.repeats; ++rep) {
    for (size_t a = 0; a < animats.size(); ++a) {
      for (size_t c = 0; c < n; ++c) {
        Run run = RunEvaluation(animats[a].genome, configs[c][a]);
        seconds[c][a].push_back(run.seconds);
        cpu_seconds[c][a].push_back(run.cpu_seconds);
        if (rep == 0) {
          runs[c][a] = std::move(run);
        } else if (!run.SameBits(runs[c][a])) {
          deterministic[c][a] = false;
        }
      }
    }
    say(std::string("repetition ") + std::to_string(rep + 1) + "/" +
        std::to_string(report.repeats) + ": " + std::to_string(elapsed()) +
        " s");
  }

  for (size_t c = 0; c < n; ++c) {
    CandidateResult& result = results[loaded_index[c]];
    for (size_t a = 0; a < animats.size(); ++a) {
      const Run& run = runs[c][a];
      AnimatResult row;
      row.animat = animats[a].name;
      row.evolved = animats[a].evolved;
      row.status = EvalStatusName(run.status);
      row.reason = run.reason;
      row.fitness = run.fitness;
      row.max_overlap = run.max_overlap;
      row.reference_fitness = reference[a].fitness;
      row.fitness_error = FitnessError(run, reference[a]);
      row.trajectory_error = TrajectoryError(run, reference[a]);
      row.ms = Median(seconds[c][a]) * 1e3;
      row.cpu_ms = Median(cpu_seconds[c][a]) * 1e3;
      row.state_hash = run.state_hash;
      row.deterministic = deterministic[c][a];
      row.converged = report.converged[a];
      result.animats.push_back(std::move(row));
    }
    Summarise(&result);
    result.order_swaps =
        OrderSwaps(runs[c], reference, report.converged, &result.order_pairs);
  }

  // The effect of the float or Bullet option alone, against the candidate
  // without it. Float arithmetic that changes no bit is not in effect; the
  // Bullet backend may legitimately give the same bits as native
  // semi-implicit Euler (it performs the same operations).
  std::vector<Candidate> measured;
  for (const CandidateResult& r : results) measured.push_back(r.candidate);
  for (size_t c = 0; c < n; ++c) {
    CandidateResult& result = results[loaded_index[c]];
    const int other = Counterpart(measured, result.candidate);
    if (other < 0 || results[other].animats.empty()) continue;
    size_t other_c = 0;
    while (loaded_index[other_c] != other) ++other_c;
    const std::vector<Run>& mine = runs[c];
    const std::vector<Run>& theirs = runs[other_c];
    bool identical = true;
    std::vector<double> difference;
    for (size_t a = 0; a < animats.size(); ++a) {
      identical = identical && mine[a].SameBits(theirs[a]);
      difference.push_back(mine[a].ok() && theirs[a].ok()
                               ? std::abs(mine[a].fitness - theirs[a].fitness) /
                                     reference[a].fitness
                               : kInfinity);
    }
    const std::string label = results[other].candidate.Label();
    result.counterpart = label;
    result.counterpart_median = Median(difference);
    result.counterpart_p90 = Percentile90(difference);
    result.counterpart_max = Quantile(difference, 1.0);
    if (!identical) continue;
    if (result.candidate.backend != "BULLET") {
      result.error = "no effect: bit-identical to " + label +
                     " on every animat (float arithmetic not in effect in "
                     "this build)";
    } else {
      result.note = "bit-identical to " + label + " on every animat";
    }
  }

  // The Pareto front of median time against median fitness error.
  std::vector<CostError> points;
  std::vector<int> point_owner;
  for (size_t i = 0; i < results.size(); ++i) {
    if (!results[i].Eligible()) continue;
    points.push_back({results[i].ms_median, results[i].fitness_error_median});
    point_owner.push_back(static_cast<int>(i));
  }
  for (int p : ParetoFront(points)) results[point_owner[p]].on_front = true;

  report.rule_choice = RuleChoice(results);
  report.candidates = std::move(results);
  report.machine += std::string(", ") + LoadAverage() + " at the end";
  report.total_seconds = elapsed();
  return report;
}

}  // namespace animat::accuracy
