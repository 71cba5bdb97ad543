#include "master/run/evolution_run.h"

#include <algorithm>

#include "common/evaluation/evaluator.h"
#include "common/genome/genome_proto.h"
#include "common/protocol/protocol.h"
#include "master/lineage/queries.h"

namespace animat {
namespace {

// Results are committed at least this often (and before any decision that
// reads them back).
constexpr double kFlushSeconds = 0.2;
constexpr size_t kFlushCount = 5000;
// While a generation is written, workers are served at least this often,
// between chunks of at most this many offspring.
constexpr double kServeSeconds = 0.01;
constexpr size_t kWriteChunk = 64;

std::vector<Scored> ToScored(const std::vector<lineage::Score>& scores) {
  std::vector<Scored> scored;
  for (const lineage::Score& s : scores) scored.push_back({s.id, s.fitness});
  return scored;
}

// A generation's statistics from its members ranked best first.
lineage::GenerationStats Statistics(const std::vector<Scored>& ranked) {
  lineage::GenerationStats stats;
  std::vector<double> fitness;  // Best first.
  for (const Scored& s : ranked) {
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
  return stats;
}

void Submit(const std::vector<lineage::NewIndividual>& made,
            EvaluationService* evaluators) {
  for (const lineage::NewIndividual& n : made) {
    if (n.serialized) {
      evaluators->Submit(n.id, *n.serialized);
    } else {
      evaluators->Submit(n.id, n.genome);
    }
  }
}

}  // namespace

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
        plan.run_id, plan.generations_made, RunSettingsToProto(plan.settings),
        protocol::BuildId(), ConfigChangeReason(plan));
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

void EvolutionRun::AwaitedOffspring::Expect(uint64_t first_id, size_t count) {
  first = first_id;
  awaited.assign(count, true);
  left = count;
}

void EvolutionRun::AwaitedOffspring::Record(
    const std::vector<lineage::Evaluation>& committed) {
  for (const lineage::Evaluation& e : committed) Record(e.id);
}

void EvolutionRun::AwaitedOffspring::Record(uint64_t id) {
  const uint64_t i = id - first;
  if (id >= first && i < awaited.size() && awaited[i]) {
    awaited[i] = false;
    --left;
  }
}

Status EvolutionRun::Run(EvaluationService* evaluators,
                         const std::atomic<bool>& stop,
                         const Progress& progress) {
  clock_ = &evaluators->clock();
  started_ = clock_->Seconds();
  Status status = SubmitUnevaluated(evaluators);
  if (status.ok()) status = Advance(evaluators, progress);
  double last_flush = clock_->Seconds();
  while (status.ok() && !finished_ && !stop.load()) {
    status = Serve(evaluators, 100);
    if (!status.ok()) break;
    const double now = clock_->Seconds();
    if (!unsaved_.empty() &&
        (now - last_flush >= kFlushSeconds || unsaved_.size() >= kFlushCount ||
         evaluators->pending() == 0)) {
      status = Flush(evaluators);
      last_flush = now;
      // Nothing can advance while the latest generation awaits results;
      // with nothing pending at all, the store is asked in any case.
      if (status.ok() && (awaited_.left == 0 || evaluators->pending() == 0)) {
        status = Advance(evaluators, progress);
      }
    }
  }
  Status flushed = Flush(evaluators);
  return status.ok() ? flushed : status;
}

Status EvolutionRun::SubmitUnevaluated(EvaluationService* evaluators) {
  Result<std::vector<uint64_t>> pending = store_->Unevaluated(run_id_);
  if (!pending.ok()) return pending.status();
  for (uint64_t id : *pending) {
    Result<lineage::IndividualRow> row = store_->Individual(run_id_, id);
    if (!row.ok()) return row.status();
    evaluators->Submit(id, row->genome);
  }
  if (!pending->empty()) {
    log_(std::to_string(pending->size()) + " evaluations pending");
  }
  return Status::Ok();
}

Status EvolutionRun::Serve(EvaluationService* evaluators, int timeout_ms) {
  Status status;
  for (Completion& c : evaluators->Poll(timeout_ms)) {
    if (c.null_evaluation) {
      // Reported once; the rest of the batch is still recorded.
      if (status.ok()) {
        status = Status::Internal(
            "a null-evaluation worker's result for individual " +
            std::to_string(c.individual) +
            " reached the run, which records only real evaluations; not "
            "recorded");
      }
      continue;
    }
    lineage::Evaluation e;
    e.id = c.individual;
    e.result = std::move(c.result);
    e.wall_seconds = c.wall_seconds;
    e.worker = std::move(c.worker);
    e.isa = std::move(c.isa);
    unsaved_.push_back(std::move(e));
    ++evaluations_;
  }
  last_served_ = clock_->Seconds();
  return status;
}

Status EvolutionRun::Flush(EvaluationService* evaluators) {
  if (unsaved_.empty()) return Status::Ok();
  Status status = store_->RecordEvaluations(run_id_, unsaved_);
  if (!status.ok()) return status;
  // Recorded: their workers may forget them.
  std::vector<uint64_t> recorded;
  recorded.reserve(unsaved_.size());
  for (const lineage::Evaluation& e : unsaved_) recorded.push_back(e.id);
  evaluators->Acknowledge(recorded);
  if (initial_ != nullptr) initial_->Record(unsaved_);
  awaited_.Record(unsaved_);
  unsaved_.clear();
  return status;
}

Status EvolutionRun::Advance(EvaluationService* evaluators,
                             const Progress& progress) {
  // The scores of the generation completed last in this call, if any.
  int completed = -1;
  std::vector<lineage::Score> completed_scores;
  for (;;) {
    Result<std::optional<lineage::GenerationRow>> latest =
        store_->LatestGenerationHead(run_id_);
    if (!latest.ok()) return latest.status();
    if (!latest->has_value()) {
      bool changed = false;
      Status status = AdvanceInitial(evaluators, &changed);
      if (!status.ok() || !changed) return status;
      continue;
    }
    const lineage::GenerationRow& generation = **latest;
    if (!generation.complete) {
      // Offspring still out: the store would say the same.
      if (awaited_.left > 0 && evaluators->pending() > 0) return Status::Ok();
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
    Result<int> length = Length(generation.generation);
    if (!length.ok()) return length.status();
    if (generation.generation + 1 >= *length) {
      return Finish(generation.generation + 1);
    }
    Status status = MakeGeneration(
        generation.generation + 1,
        completed == generation.generation ? &completed_scores : nullptr,
        evaluators);
    if (!status.ok()) return status;
  }
}

Status EvolutionRun::Finish(int generations) {
  if (finished_) return Status::Ok();
  finished_ = true;
  Status status = store_->FinishRun(run_id_);
  if (!status.ok()) return status;
  log_("run " + std::to_string(run_id_) + " finished after " +
       std::to_string(generations) + " generations");
  return Status::Ok();
}

Result<int> EvolutionRun::Length(int completed) {
  const EvolutionParams& p = params();
  if (length_) return *length_;
  if (!EvolutionExtends(p) || completed + 1 < p.generations) {
    return p.generations;
  }
  Result<std::vector<lineage::CompletedGeneration>> done =
      lineage::CompletedGenerations(*store_, run_id_);
  if (!done.ok()) return done.status();
  std::vector<std::optional<double>> bests;
  for (const lineage::CompletedGeneration& g : *done) {
    bests.push_back(g.stats.best);
  }
  length_ = EvolutionLength(p, bests);
  const int last = p.generations - 1;
  const int before = last - p.extend_window;
  log_(*length_ > p.generations
           ? "still improving at generation " + std::to_string(last) +
                 " (a new best since generation " + std::to_string(before) +
                 "): goes on to " + std::to_string(*length_) + " generations"
           : "no new best since generation " + std::to_string(before) +
                 ": ends at " + std::to_string(*length_) + " generations");
  return *length_;
}

Status EvolutionRun::AdvanceInitial(EvaluationService* evaluators,
                                    bool* changed) {
  *changed = false;
  if (initial_ == nullptr) {
    Result<std::unique_ptr<InitialPopulation>> loaded =
        InitialPopulation::Load(store_, run_id_);
    if (!loaded.ok()) return loaded.status();
    initial_ = std::move(loaded).value();
  }
  InitialPopulation::Step step = initial_->Next(params());
  if (!step.block.empty()) {
    Status status = store_->AddIndividuals(run_id_, step.block);
    if (!status.ok()) return status;
    initial_->Made(step.block);
    Submit(step.block, evaluators);
    *changed = true;
  } else if (!step.population.empty()) {
    Status status = store_->AddGeneration(run_id_, 0, step.population);
    if (!status.ok()) return status;
    initial_.reset();  // No longer needed.
    log_("initial population chosen from the first " +
         std::to_string(step.population.back() + 1) + " random genomes");
    *changed = true;
  }
  return Status::Ok();
}

Status EvolutionRun::CompleteGeneration(
    int generation, const std::vector<lineage::Score>& scores,
    const Progress& progress) {
  const std::vector<Scored> ranked = Rank(ToScored(scores));
  std::vector<uint64_t> order;
  for (const Scored& s : ranked) order.push_back(s.id);
  const lineage::GenerationStats stats = Statistics(ranked);
  Status status = store_->CompleteGeneration(run_id_, generation, order, stats);
  if (!status.ok()) return status;
  Report(generation, stats, progress);
  return Status::Ok();
}

void EvolutionRun::Report(int generation, const lineage::GenerationStats& stats,
                          const Progress& progress) {
  // Rate and estimate from the generation just finished (the initial
  // population's thousands of quick failures would mislead an average).
  const double now = clock_->Seconds();
  const double since = now - (last_report_ > 0 ? last_report_ : started_);
  const int64_t done = evaluations_ - evaluations_at_last_report_;
  last_report_ = now;
  evaluations_at_last_report_ = evaluations_;
  if (!progress) return;
  GenerationReport report;
  report.generation = generation;
  report.generations = length_.value_or(params().generations);
  report.stats = stats;
  report.evaluations = evaluations_;
  report.evaluations_per_second =
      since > 0 ? static_cast<double>(done) / since : 0.0;
  if (generation > 0 && since > 0) {
    report.seconds_left =
        static_cast<double>(report.generations - generation - 1) * since;
  }
  progress(report);
}

Result<std::vector<Scored>> EvolutionRun::Parents(
    int generation, const std::vector<lineage::Score>* scores) {
  std::vector<Scored> scored;
  if (genomes_generation_ == generation) {
    // Made by this process (the store holds the same).
    if (scores != nullptr) {
      scored = ToScored(*scores);
    } else {
      Result<std::vector<lineage::Score>> stored =
          store_->MemberScores(run_id_, generation);
      if (!stored.ok()) return stored.status();
      scored = ToScored(*stored);
    }
  } else {
    Result<std::vector<lineage::MemberGenome>> members =
        store_->MemberGenomes(run_id_, generation);
    if (!members.ok()) return members.status();
    genomes_ = GenomesById();
    for (const lineage::MemberGenome& member : *members) {
      Result<Genome> genome = GenomeFromProto(member.genome);
      if (!genome.ok()) {
        return genome.status().WithPrefix("stored genome of individual " +
                                          std::to_string(member.id));
      }
      genomes_.ids.push_back(member.id);  // Increasing.
      genomes_.genomes.push_back(std::move(genome).value());
      scored.push_back({member.id, member.fitness});
    }
    genomes_generation_ = generation;
  }
  for (const Scored& s : scored) {
    if (genomes_.Find(s.id) == nullptr) {
      return Status::Internal("no genome of member " + std::to_string(s.id) +
                              " of generation " + std::to_string(generation));
    }
  }
  return scored;
}

Status EvolutionRun::MakeGeneration(
    int generation, const std::vector<lineage::Score>* previous_scores,
    EvaluationService* evaluators) {
  const EvolutionParams& p = params();
  Result<std::vector<Scored>> parents =
      Parents(generation - 1, previous_scores);
  if (!parents.ok()) return parents.status();
  std::vector<Scored> ranked = Rank(std::move(parents).value());
  // The elites (kept, all older than the offspring to come), then the
  // offspring, ids *next, *next + 1, ...
  std::vector<uint64_t> members;
  for (int e = 0; e < p.elite && e < static_cast<int>(ranked.size()); ++e) {
    members.push_back(ranked[e].id);
  }
  // The parents' keys, made once per genome: kept from the generation
  // that made it, or made here after a resume.
  OffspringPipeline::KeyFunction key_of;
  if (evaluators->results_follow_genome()) {
    const ModelConfig* model = &settings_.model;
    key_of = [model](const Genome& genome) {
      return EvaluationKey(genome, *model);
    };
    if (genomes_.keys.size() != genomes_.ids.size()) {
      genomes_.keys.clear();
      for (const Genome& genome : genomes_.genomes) {
        genomes_.keys.push_back(key_of(genome));
      }
    }
  }
  GenomesById next_genomes;
  next_genomes.ids = members;
  std::sort(next_genomes.ids.begin(), next_genomes.ids.end());
  for (uint64_t id : next_genomes.ids) {
    const size_t index = *genomes_.IndexOf(id);
    next_genomes.genomes.push_back(genomes_.genomes[index]);
    if (key_of) next_genomes.keys.push_back(genomes_.keys[index]);
  }
  Result<uint64_t> next = store_->NextId(run_id_);
  if (!next.ok()) return next.status();
  const size_t population = static_cast<size_t>(p.population);
  const size_t count =
      members.size() < population ? population - members.size() : 0;
  for (size_t i = 0; i < count; ++i) members.push_back(*next + i);

  // The parents by what their evaluation read of their genome (ids
  // increasing, so the lowest id first), when an evaluation may stand for
  // another of the same key.
  std::map<std::string, uint64_t> parents_by_key;
  if (key_of) {
    for (size_t i = 0; i < genomes_.ids.size(); ++i) {
      if (genomes_.keys[i]) {
        parents_by_key.emplace(*genomes_.keys[i], genomes_.ids[i]);
      }
    }
  }
  OffspringPipeline pipeline(generation, *next, count, std::move(ranked),
                             &genomes_, p, std::move(key_of));
  std::vector<uint64_t> reused;
  Result<std::vector<lineage::NewIndividual>> offspring =
      WriteGeneration(generation, std::move(members), &pipeline, parents_by_key,
                      evaluators, &reused);
  if (!offspring.ok()) return offspring.status();
  std::vector<Genome> made = pipeline.TakeGenomes();
  std::vector<std::optional<std::string>> made_keys = pipeline.TakeKeys();
  for (size_t i = 0; i < count; ++i) {
    next_genomes.ids.push_back(*next + i);
    next_genomes.genomes.push_back(std::move(made[i]));
    if (!made_keys.empty())
      next_genomes.keys.push_back(std::move(made_keys[i]));
  }
  genomes_ = std::move(next_genomes);
  genomes_generation_ = generation;
  awaited_.Expect(*next, count);
  for (uint64_t id : reused) awaited_.Record(id);
  Submit(*offspring, evaluators);
  return Status::Ok();
}

Result<std::vector<lineage::NewIndividual>> EvolutionRun::WriteGeneration(
    int generation, std::vector<uint64_t> members, OffspringPipeline* pipeline,
    const std::map<std::string, uint64_t>& parents_by_key,
    EvaluationService* evaluators, std::vector<uint64_t>* reused) {
  Result<std::unique_ptr<lineage::GenerationWrite>> write =
      store_->BeginGeneration(run_id_, generation, std::move(members));
  if (!write.ok()) return write.status();
  std::vector<lineage::NewIndividual> written;
  for (;;) {
    std::vector<lineage::NewIndividual> chunk = pipeline->Next(kWriteChunk);
    if (chunk.empty()) break;
    Status status = (*write)->Add(chunk);
    if (!status.ok()) return status;
    for (lineage::NewIndividual& n : chunk) {
      const std::optional<std::string>& key = pipeline->KeyOf(n.id);
      const auto parent =
          key ? parents_by_key.find(*key) : parents_by_key.end();
      if (parent != parents_by_key.end()) {
        Result<bool> copied = (*write)->Reuse(n.id, parent->second);
        if (!copied.ok()) return copied.status();
        if (*copied) {
          reused->push_back(n.id);
          continue;
        }
      }
      written.push_back(std::move(n));
    }
    // Workers are served between chunks (heartbeats, results of work
    // already out), so a large generation does not look like a lost
    // master. The results wait in memory for the next Flush.
    if (clock_->Seconds() - last_served_ >= kServeSeconds) {
      status = Serve(evaluators, 0);
      if (!status.ok()) return status;
    }
  }
  Status status = (*write)->Commit();
  if (!status.ok()) return status;
  return written;
}

}  // namespace animat
