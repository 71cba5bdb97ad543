#include "master/run/evolution_run.h"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <thread>

#include "common/base/rng.h"
#include "common/genome/genome_proto.h"
#include "common/protocol/genome_wire.h"
#include "common/protocol/protocol.h"

namespace animat {
namespace {

// Results are committed at least this often (and before any decision that
// reads them back).
constexpr double kFlushSeconds = 0.2;
constexpr size_t kFlushCount = 5000;
// While making a generation, workers are served at least this often.
constexpr double kServeSeconds = 0.01;

std::vector<Scored> ToScored(const std::vector<lineage::Score>& scores) {
  std::vector<Scored> scored;
  for (const lineage::Score& s : scores) scored.push_back({s.id, s.fitness});
  return scored;
}

}  // namespace

const Genome* EvolutionRun::GenomesById::Find(uint64_t id) const {
  const auto it = std::lower_bound(ids.begin(), ids.end(), id);
  if (it == ids.end() || *it != id) return nullptr;
  return &genomes[static_cast<size_t>(it - ids.begin())];
}

double NullEvaluationFitness(uint64_t seed, uint64_t id) {
  return RandomStream(seed, id, StreamPurpose::kNullFitness).NextDouble();
}

Result<RunPlan> EvolutionRun::PlanStart(lineage::Store* store,
                                        const RunSettings& settings) {
  Result<std::vector<lineage::RunRow>> runs = store->Runs();
  if (!runs.ok()) return runs.status();
  if (!runs->empty()) {
    return Status::InvalidArgument(
        store->path() +
        ": already holds a run; continue it with --resume, or use another "
        "database");
  }
  RunPlan plan;
  plan.settings = settings;
  return plan;
}

namespace {

// What differs between the settings given and the stored ones, and
// between this build and the run's, beyond the number of generations
// (which decides no individual).
std::vector<std::string> ResumeProblems(
    const std::optional<RunSettings>& settings, const RunSettings& stored,
    const lineage::RunRow& row) {
  const auto comparable = [](RunSettings s) {
    s.evolution.generations = 0;
    return protocol::MessageHash(RunSettingsToProto(s));
  };
  std::vector<std::string> problems;
  if (settings && comparable(*settings) != comparable(stored)) {
    problems.push_back("the configuration given differs from the run's");
  }
  if (row.build_id != protocol::BuildId()) {
    problems.push_back("the run was evaluated by build \"" + row.build_id +
                       "\", this is \"" + protocol::BuildId() +
                       "\" (results could differ in the last bits)");
  }
  return problems;
}

}  // namespace

Result<RunPlan> EvolutionRun::PlanResume(
    lineage::Store* store, const std::optional<RunSettings>& settings,
    bool force, std::optional<int> generations) {
  Result<std::vector<lineage::RunRow>> runs = store->Runs();
  if (!runs.ok()) return runs.status();
  if (runs->empty()) {
    return Status::NotFound(store->path() +
                            ": no run to resume; start one with --config");
  }
  const lineage::RunRow& row = runs->back();
  RunSettings stored;
  Status status = RunSettingsFromProto(row.config, &stored);
  if (!status.ok()) {
    return status.WithPrefix(store->path() + ": the stored configuration");
  }
  RunPlan plan;
  plan.run_id = row.run_id;
  plan.state = row.state;
  Result<std::optional<lineage::GenerationRow>> latest =
      store->LatestGenerationHead(row.run_id);
  if (!latest.ok()) return latest.status();
  plan.generations_made = *latest ? (*latest)->generation + 1 : 0;
  std::vector<std::string> problems = ResumeProblems(settings, stored, row);
  if (!problems.empty() && !force) {
    std::string message = store->path() + ": refusing to resume:";
    for (const std::string& p : problems) message += " " + p + ";";
    return Status::InvalidArgument(message + " --force resumes anyway");
  }
  plan.settings = settings && force ? *settings : stored;
  if (generations) plan.settings.evolution.generations = *generations;
  plan.update_config =
      plan.settings.evolution.generations != stored.evolution.generations ||
      !problems.empty();
  plan.forced = std::move(problems);
  return plan;
}

Result<std::unique_ptr<EvolutionRun>> EvolutionRun::Begin(lineage::Store* store,
                                                          const RunPlan& plan,
                                                          LogSink log) {
  if (plan.run_id == 0) {
    Result<int64_t> run = store->CreateRun(plan.settings.evolution.seed,
                                           RunSettingsToProto(plan.settings),
                                           protocol::BuildId());
    if (!run.ok()) return run.status();
    log("run " + std::to_string(*run) + " started, seed " +
        std::to_string(plan.settings.evolution.seed));
    return std::unique_ptr<EvolutionRun>(
        new EvolutionRun(store, plan.settings, *run, std::move(log)));
  }
  // Rewriting the run's generations below what it has made would end it
  // at once and misstate it.
  if (plan.update_config &&
      plan.settings.evolution.generations < plan.generations_made) {
    return Status::InvalidArgument(
        store->path() + ": run " + std::to_string(plan.run_id) + " has made " +
        std::to_string(plan.generations_made) + " generations, more than the " +
        std::to_string(plan.settings.evolution.generations) + " asked for");
  }
  for (const std::string& p : plan.forced) {
    log("resuming anyway (--force): " + p);
  }
  if (plan.update_config) {
    // The run's recorded configuration and build are what it now runs
    // with (so the next resume by this build needs no --force).
    Status status = store->UpdateRunConfig(
        plan.run_id, RunSettingsToProto(plan.settings), protocol::BuildId());
    if (!status.ok()) return status;
  }
  log("resuming run " + std::to_string(plan.run_id));
  return std::unique_ptr<EvolutionRun>(
      new EvolutionRun(store, plan.settings, plan.run_id, std::move(log)));
}

Result<std::unique_ptr<EvolutionRun>> EvolutionRun::Start(
    lineage::Store* store, const RunSettings& settings, LogSink log) {
  Result<RunPlan> plan = PlanStart(store, settings);
  if (!plan.ok()) return plan.status();
  return Begin(store, *plan, std::move(log));
}

Result<std::unique_ptr<EvolutionRun>> EvolutionRun::Resume(
    lineage::Store* store, const std::optional<RunSettings>& settings,
    bool force, std::optional<int> generations, LogSink log) {
  Result<RunPlan> plan = PlanResume(store, settings, force, generations);
  if (!plan.ok()) return plan.status();
  return Begin(store, *plan, std::move(log));
}

Status EvolutionRun::Submit(const std::vector<lineage::NewIndividual>& made,
                            Dispatcher* dispatcher) {
  for (const lineage::NewIndividual& n : made) {
    if (n.serialized) {
      dispatcher->Submit(n.id, *n.serialized);
    } else {
      dispatcher->Submit(n.id, n.genome);
    }
  }
  return Status::Ok();
}

Status EvolutionRun::Flush(Dispatcher* dispatcher) {
  if (unsaved_.empty()) return Status::Ok();
  Status status = store_->RecordEvaluations(run_id_, unsaved_);
  if (!status.ok()) return status;
  // Recorded: their workers may forget them.
  std::vector<uint64_t> recorded;
  recorded.reserve(unsaved_.size());
  for (const lineage::Evaluation& e : unsaved_) recorded.push_back(e.id);
  dispatcher->Acknowledge(recorded);
  for (const lineage::Evaluation& e : unsaved_) {
    // The store keeps an individual's first evaluation; so does the copy.
    if (e.id < candidates_.size() && !candidates_[e.id].evaluated) {
      lineage::Score& c = candidates_[e.id];
      c.evaluated = true;
      if (e.result.has_fitness()) c.fitness = e.result.fitness();
    }
    const uint64_t i = e.id - awaited_first_;
    if (e.id >= awaited_first_ && i < awaited_.size() && awaited_[i]) {
      awaited_[i] = false;
      --awaited_left_;
    }
  }
  unsaved_.clear();
  return status;
}

Status EvolutionRun::Run(
    Dispatcher* dispatcher, const std::atomic<bool>& stop,
    const std::function<void(const GenerationReport&)>& progress) {
  clock_ = &dispatcher->clock();
  started_ = clock_->Seconds();
  // Whatever was made and not evaluated before (a resumed run) goes out
  // first.
  Result<std::vector<uint64_t>> pending = store_->Unevaluated(run_id_);
  if (!pending.ok()) return pending.status();
  for (uint64_t id : *pending) {
    Result<lineage::IndividualRow> row = store_->Individual(run_id_, id);
    if (!row.ok()) return row.status();
    dispatcher->Submit(id, row->genome);
  }
  if (!pending->empty()) {
    log_(std::to_string(pending->size()) + " evaluations pending");
  }
  Status status = Advance(dispatcher, progress);
  double last_flush = clock_->Seconds();
  while (status.ok() && !finished_ && !stop.load()) {
    status = Serve(dispatcher, 100);
    if (!status.ok()) break;
    const double now = clock_->Seconds();
    if (!unsaved_.empty() &&
        (now - last_flush >= kFlushSeconds || unsaved_.size() >= kFlushCount ||
         dispatcher->pending() == 0)) {
      status = Flush(dispatcher);
      last_flush = now;
      // Nothing can advance while the latest generation awaits results;
      // with nothing pending at all, the store is asked in any case.
      if (status.ok() && (awaited_left_ == 0 || dispatcher->pending() == 0)) {
        status = Advance(dispatcher, progress);
      }
    }
  }
  Status flushed = Flush(dispatcher);
  return status.ok() ? flushed : status;
}

Status EvolutionRun::Serve(Dispatcher* dispatcher, int timeout_ms) {
  Status status;
  for (Completion& c : dispatcher->Poll(timeout_ms)) {
    if (c.null_evaluation) {
      if (!score_null_evaluations_) {
        // Reported once; the rest of the batch is still recorded.
        if (status.ok()) {
          status = Status::Internal(
              "a null-evaluation worker's result for individual " +
              std::to_string(c.individual) +
              " reached a run that does not score them; not recorded");
        }
        continue;
      }
      c.result.Clear();
      c.result.set_status(v1::EvaluationResult::OK);
      c.result.set_fitness(NullEvaluationFitness(params().seed, c.individual));
    }
    lineage::Evaluation e;
    e.id = c.individual;
    e.result = std::move(c.result);
    e.wall_seconds = c.wall_seconds;
    e.worker = std::move(c.worker);
    unsaved_.push_back(std::move(e));
    ++evaluations_;
  }
  last_served_ = clock_->Seconds();
  return status;
}

Status EvolutionRun::Advance(
    Dispatcher* dispatcher,
    const std::function<void(const GenerationReport&)>& progress) {
  // The scores of the generation completed last in this call, if any.
  int completed = -1;
  std::vector<lineage::Score> completed_scores;
  for (;;) {
    Result<std::optional<lineage::GenerationRow>> latest =
        store_->LatestGenerationHead(run_id_);
    if (!latest.ok()) return latest.status();
    if (!latest->has_value()) {
      bool changed = false;
      Status status = AdvanceInitial(dispatcher, &changed);
      if (!status.ok() || !changed) return status;
      continue;
    }
    const lineage::GenerationRow& generation = **latest;
    if (!generation.complete) {
      // Offspring still out: the store would say the same.
      if (awaited_left_ > 0 && dispatcher->pending() > 0) return Status::Ok();
      Result<std::vector<lineage::Score>> scores =
          store_->MemberScores(run_id_, generation.generation);
      if (!scores.ok()) return scores.status();
      for (const lineage::Score& s : *scores) {
        if (!s.evaluated) return Status::Ok();  // Waiting for results.
      }
      Status status =
          CompleteGeneration(generation.generation, *scores, progress);
      if (!status.ok()) return status;
      completed = generation.generation;
      completed_scores = std::move(scores).value();
      continue;
    }
    if (generation.generation + 1 >= params().generations) {
      if (!finished_) {
        finished_ = true;
        Status status = store_->FinishRun(run_id_);
        if (!status.ok()) return status;
        log_("run " + std::to_string(run_id_) + " finished after " +
             std::to_string(generation.generation + 1) + " generations");
      }
      return Status::Ok();
    }
    Status status = MakeGeneration(
        generation.generation + 1,
        completed == generation.generation ? &completed_scores : nullptr,
        dispatcher);
    if (!status.ok()) return status;
  }
}

Status EvolutionRun::AdvanceInitial(Dispatcher* dispatcher, bool* changed) {
  *changed = false;
  const EvolutionParams& p = params();
  const size_t population = static_cast<size_t>(p.population);
  if (!candidates_loaded_) {
    Result<std::vector<lineage::Score>> stored = store_->ScoresOf(run_id_, 0);
    if (!stored.ok()) return stored.status();
    for (size_t i = 0; i < stored->size(); ++i) {
      if ((*stored)[i].id != i) {
        return Status::Internal(store_->path() +
                                ": the random candidates of generation 0 are "
                                "not numbered 0, 1, ...: individual " +
                                std::to_string((*stored)[i].id) +
                                " is candidate " + std::to_string(i));
      }
    }
    candidates_ = std::move(stored).value();
    candidates_loaded_ = true;
  }
  const std::vector<lineage::Score>* candidates = &candidates_;
  // The evaluated prefix (candidates [0, prefix) all evaluated) and the
  // accepted candidates in it, in id order.
  uint64_t prefix = 0;
  std::vector<uint64_t> accepted;
  for (const lineage::Score& c : *candidates) {
    if (!c.evaluated) break;
    prefix = c.id + 1;
    if (c.fitness && *c.fitness > p.initial_min_fitness) {
      accepted.push_back(c.id);
    }
  }
  // Block k (ids k*B .. (k+1)*B - 1) is made when blocks 0..k-2 are all
  // evaluated and hold fewer than `population` accepted candidates: a
  // decision on evaluated blocks only, so every run of this seed makes the
  // same blocks, and one block is always ahead to keep workers busy. It
  // comes before choosing the population, which could otherwise end the
  // making of blocks at a moment that depends on timing.
  const uint64_t k = candidates->size() / kCandidateBlock;
  bool make = k < 2;
  if (!make && prefix >= (k - 1) * kCandidateBlock) {
    const uint64_t limit = (k - 1) * kCandidateBlock;
    size_t before = 0;
    while (before < accepted.size() && accepted[before] < limit) ++before;
    make = before < population;
  }
  if (make) {
    std::vector<lineage::NewIndividual> batch;
    for (uint64_t id = k * kCandidateBlock; id < (k + 1) * kCandidateBlock;
         ++id) {
      lineage::NewIndividual n;
      n.id = id;
      n.generation = 0;
      n.operators = {"random"};
      n.serialized = protocol::SerializeGenome(InitialCandidate(id, p));
      batch.push_back(std::move(n));
    }
    Status status = store_->AddIndividuals(run_id_, batch);
    if (!status.ok()) return status;
    for (const lineage::NewIndividual& n : batch) {
      lineage::Score score;
      score.id = n.id;
      candidates_.push_back(score);
    }
    *changed = true;
    return Submit(batch, dispatcher);
  }
  // The population: the first `population` candidates above the
  // threshold, once every candidate before the last of them is evaluated.
  if (accepted.size() >= population) {
    accepted.resize(population);
    Status status = store_->AddGeneration(run_id_, 0, accepted);
    if (!status.ok()) return status;
    candidates_ = std::vector<lineage::Score>();  // No longer needed.
    log_("initial population chosen from the first " +
         std::to_string(accepted.back() + 1) + " random genomes");
    *changed = true;
  }
  return Status::Ok();
}

Status EvolutionRun::CompleteGeneration(
    int generation, const std::vector<lineage::Score>& scores,
    const std::function<void(const GenerationReport&)>& progress) {
  const std::vector<Scored> ranked = Rank(ToScored(scores));
  lineage::GenerationStats stats;
  std::vector<uint64_t> order;
  std::vector<double> fitness;  // Best first.
  for (const Scored& s : ranked) {
    order.push_back(s.id);
    if (s.fitness) fitness.push_back(*s.fitness);
  }
  stats.evaluated = static_cast<int>(fitness.size());
  stats.failed = static_cast<int>(ranked.size() - fitness.size());
  if (!fitness.empty()) {
    stats.best_id = ranked.front().id;
    stats.best = fitness.front();
    double sum = 0.0;
    for (double f : fitness) sum += f;  // In rank order: fixed.
    stats.mean = sum / static_cast<double>(fitness.size());
    const size_t n = fitness.size();
    stats.median = n % 2 == 1 ? fitness[n / 2]
                              : 0.5 * (fitness[n / 2 - 1] + fitness[n / 2]);
  }
  Status status = store_->CompleteGeneration(run_id_, generation, order, stats);
  if (!status.ok()) return status;
  // Rate and estimate from the generation just finished (the initial
  // population's thousands of quick failures would mislead an average).
  const double now = clock_->Seconds();
  const double since = now - (last_report_ > 0 ? last_report_ : started_);
  const int64_t done = evaluations_ - evaluations_at_last_report_;
  last_report_ = now;
  evaluations_at_last_report_ = evaluations_;
  if (progress) {
    GenerationReport report;
    report.generation = generation;
    report.generations = params().generations;
    report.stats = stats;
    report.evaluations = evaluations_;
    report.evaluations_per_second =
        since > 0 ? static_cast<double>(done) / since : 0.0;
    if (generation > 0 && since > 0) {
      report.seconds_left =
          static_cast<double>(params().generations - generation - 1) * since;
    }
    progress(report);
  }
  return Status::Ok();
}

Status EvolutionRun::MakeGeneration(
    int generation, const std::vector<lineage::Score>* previous_scores,
    Dispatcher* dispatcher) {
  const EvolutionParams& p = params();
  // The previous generation's genomes: those this process made (the store
  // holds the same), or else the store's.
  std::vector<Scored> scored;
  if (genomes_generation_ == generation - 1) {
    if (previous_scores != nullptr) {
      scored = ToScored(*previous_scores);
    } else {
      Result<std::vector<lineage::Score>> scores =
          store_->MemberScores(run_id_, generation - 1);
      if (!scores.ok()) return scores.status();
      scored = ToScored(*scores);
    }
  } else {
    Result<std::vector<lineage::MemberGenome>> previous =
        store_->MemberGenomes(run_id_, generation - 1);
    if (!previous.ok()) return previous.status();
    genomes_ = GenomesById();
    for (const lineage::MemberGenome& member : *previous) {
      Result<Genome> genome = GenomeFromProto(member.genome);
      if (!genome.ok()) {
        return genome.status().WithPrefix("stored genome of individual " +
                                          std::to_string(member.id));
      }
      genomes_.ids.push_back(member.id);  // Increasing.
      genomes_.genomes.push_back(std::move(genome).value());
      scored.push_back({member.id, member.fitness});
    }
    genomes_generation_ = generation - 1;
  }
  for (const Scored& s : scored) {
    if (genomes_.Find(s.id) == nullptr) {
      return Status::Internal("no genome of member " + std::to_string(s.id) +
                              " of generation " +
                              std::to_string(generation - 1));
    }
  }
  const std::vector<Scored> ranked = Rank(std::move(scored));
  std::vector<uint64_t> members;
  GenomesById next_genomes;
  next_genomes.ids.reserve(static_cast<size_t>(p.population));
  next_genomes.genomes.reserve(static_cast<size_t>(p.population));
  for (int e = 0; e < p.elite && e < static_cast<int>(ranked.size()); ++e) {
    members.push_back(ranked[e].id);
    next_genomes.ids.push_back(ranked[e].id);
  }
  // The elites by id (all older than the offspring to come).
  std::sort(next_genomes.ids.begin(), next_genomes.ids.end());
  for (uint64_t id : next_genomes.ids) {
    next_genomes.genomes.push_back(*genomes_.Find(id));
  }
  Result<uint64_t> next = store_->NextId(run_id_);
  if (!next.ok()) return next.status();
  const auto genome_of = [&](uint64_t id) -> const Genome& {
    return *genomes_.Find(id);
  };
  // The offspring take ids *next, *next + 1, ...
  const size_t population = static_cast<size_t>(p.population);
  const size_t count =
      members.size() < population ? population - members.size() : 0;
  for (size_t i = 0; i < count; ++i) members.push_back(*next + i);
  // Each offspring is a pure function of the seed, its id and the ranked
  // generation, so a second thread makes them, in id order, while this one
  // writes those made so far into the store's transaction.
  std::vector<lineage::NewIndividual> children(count);
  std::vector<Genome> child_genomes(count);
  std::atomic<size_t> made{0};
  std::atomic<bool> abandon{false};
  std::thread maker([&] {
    for (size_t i = 0; i < count && !abandon.load(std::memory_order_relaxed);
         ++i) {
      const uint64_t id = *next + i;
      Offspring offspring = MakeOffspring(id, ranked, genome_of, p);
      lineage::NewIndividual& n = children[i];
      n.id = id;
      n.generation = generation;
      n.parents = std::move(offspring.parents);
      n.operators = std::move(offspring.operators);
      n.serialized = protocol::SerializeGenome(offspring.genome);
      child_genomes[i] = std::move(offspring.genome);
      made.store(i + 1, std::memory_order_release);
      made.notify_one();
    }
  });
  // Workers are served meanwhile (heartbeats, results of work already
  // out), so a large generation does not look like a lost master.
  Status served;
  Status status = store_->AddGeneration(
      run_id_, generation, members, count,
      [&](size_t i) -> const lineage::NewIndividual& {
        if (i % 64 == 0 && served.ok() &&
            clock_->Seconds() - last_served_ >= kServeSeconds) {
          served = Serve(dispatcher, 0);
        }
        for (size_t m = made.load(std::memory_order_acquire); m <= i;
             m = made.load(std::memory_order_acquire)) {
          made.wait(m, std::memory_order_acquire);
        }
        return children[i];
      });
  abandon.store(true, std::memory_order_relaxed);
  maker.join();
  if (!status.ok()) return status;
  if (!served.ok()) return served;
  for (size_t i = 0; i < count; ++i) {
    next_genomes.ids.push_back(*next + i);
    next_genomes.genomes.push_back(std::move(child_genomes[i]));
  }
  genomes_ = std::move(next_genomes);
  genomes_generation_ = generation;
  awaited_first_ = *next;
  awaited_.assign(children.size(), true);
  awaited_left_ = children.size();
  return Submit(children, dispatcher);
}

}  // namespace animat
