// An evolutionary run driven through a dispatcher and recorded in a
// lineage store; started fresh or resumed exactly where it stopped.
//
// Determinism: every individual is a pure function of the run's seed, its
// id and the ranked generation before it (master/evolution/operators.h);
// ids are handed out in a fixed order; initial candidates come in blocks of
// kCandidateBlock, and block k + 2 is made only once blocks 0..k are all
// evaluated and have not yet given the population. So the store ends up
// with the same individuals, parents and evaluations whatever the number
// of workers, the order results arrive in, or how often the master was
// killed and resumed.
//
// Not thread-safe: one thread calls Run.
#ifndef ANIMAT_MASTER_RUN_EVOLUTION_RUN_H_
#define ANIMAT_MASTER_RUN_EVOLUTION_RUN_H_

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/base/clock.h"
#include "common/base/log.h"
#include "common/base/status.h"
#include "common/genome/genome.h"
#include "master/dispatch/dispatcher.h"
#include "master/evolution/evolution_params.h"
#include "master/evolution/operators.h"
#include "master/lineage/store.h"

namespace animat {

// Initial candidates are made this many at a time.
inline constexpr int kCandidateBlock = 1024;

// The stand-in fitness of individual `id` evaluated by a null-evaluation
// worker, for benchmarks of the master (see
// EvolutionRun::ScoreNullEvaluations): uniform in [0, 1), a pure function
// of the run's seed and the id.
double NullEvaluationFitness(uint64_t seed, uint64_t id);

// One line's worth of progress, after each generation completes.
struct GenerationReport {
  int generation = 0;
  int generations = 0;  // Of the run.
  lineage::GenerationStats stats;
  int64_t evaluations = 0;  // Since this process started.
  double evaluations_per_second = 0;
  double seconds_left = -1;  // Estimate; -1 when unknown.
};

// What starting a run, or continuing the store's run, will do: decided by
// reading the store only (EvolutionRun::PlanStart, PlanResume), so that a
// start-up that fails after planning (a port in use) leaves the store as
// it was; EvolutionRun::Begin then writes it.
struct RunPlan {
  int64_t run_id = 0;    // The run to continue; 0 for a new run.
  RunSettings settings;  // What the run runs with.
  // Of the run to continue: its state ("running" or "finished") and the
  // generations it has made.
  std::string state;
  int generations_made = 0;
  // The run's recorded configuration and build are replaced by `settings`
  // and this build (an extended run, or --force).
  bool update_config = false;
  std::vector<std::string> forced;  // What --force overrides, for the log.
};

class EvolutionRun {
 public:
  // A new run in `store`, which must hold none (kInvalidArgument
  // otherwise, saying so).
  static Result<RunPlan> PlanStart(lineage::Store* store,
                                   const RunSettings& settings);
  // Continues the store's run. Refuses, saying why, when `settings` is
  // given and differs from the stored configuration, or when the store was
  // written by another simulator build, unless `force`. `generations`, when
  // set, replaces the run's number of generations (to extend a finished
  // run).
  static Result<RunPlan> PlanResume(lineage::Store* store,
                                    const std::optional<RunSettings>& settings,
                                    bool force, std::optional<int> generations);
  // Carries out `plan` (made for `store`): creates the run, or updates its
  // recorded configuration as planned. Refuses to record fewer generations
  // than the run has made (kInvalidArgument). The store must outlive the
  // run.
  static Result<std::unique_ptr<EvolutionRun>> Begin(
      lineage::Store* store, const RunPlan& plan,
      LogSink log = Prefixed("master", StderrSink));

  // PlanStart, then Begin.
  static Result<std::unique_ptr<EvolutionRun>> Start(
      lineage::Store* store, const RunSettings& settings,
      LogSink log = Prefixed("master", StderrSink));
  // PlanResume, then Begin.
  static Result<std::unique_ptr<EvolutionRun>> Resume(
      lineage::Store* store, const std::optional<RunSettings>& settings,
      bool force, std::optional<int> generations,
      LogSink log = Prefixed("master", StderrSink));

  // Serves `dispatcher` (built with model_config(), and with
  // acknowledge_on_receipt off so that workers keep each result until it
  // is committed) until the run has all its generations or `stop` becomes
  // true; results received so far are committed before returning. `progress`,
  // if set, is called after each generation completes. The run keeps time
  // (commit intervals, rates in the reports) by the dispatcher's clock.
  Status Run(
      Dispatcher* dispatcher, const std::atomic<bool>& stop,
      const std::function<void(const GenerationReport&)>& progress = nullptr);

  // Benchmarks of the master only (bench/master_bench.cc); no command
  // line reaches it. Results of null-evaluation workers (the dispatcher
  // must accept them) are then recorded as OK with the fitness
  // NullEvaluationFitness(seed, id), through the same store writes as real
  // results, so selection proceeds generation after generation. Without
  // it, such a result is never recorded: Run fails, saying so.
  void ScoreNullEvaluations() { score_null_evaluations_ = true; }

  const ModelConfig& model_config() const { return settings_.model; }
  const EvolutionParams& params() const { return settings_.evolution; }
  int64_t run_id() const { return run_id_; }
  bool finished() const { return finished_; }

 private:
  EvolutionRun(lineage::Store* store, RunSettings settings, int64_t run_id,
               LogSink log)
      : store_(store),
        settings_(std::move(settings)),
        run_id_(run_id),
        log_(std::move(log)) {}

  // Advances as far as the store allows: makes candidate blocks, chooses
  // the initial population, completes generations, makes the next one.
  // New individuals are submitted to `dispatcher`.
  Status Advance(Dispatcher* dispatcher,
                 const std::function<void(const GenerationReport&)>& progress);
  Status AdvanceInitial(Dispatcher* dispatcher, bool* changed);
  // `scores`: of every member, all evaluated.
  Status CompleteGeneration(
      int generation, const std::vector<lineage::Score>& scores,
      const std::function<void(const GenerationReport&)>& progress);
  // `previous_scores`: of generation - 1's members, when at hand.
  Status MakeGeneration(int generation,
                        const std::vector<lineage::Score>* previous_scores,
                        Dispatcher* dispatcher);
  Status Submit(const std::vector<lineage::NewIndividual>& made,
                Dispatcher* dispatcher);
  // Polls `dispatcher` for up to `timeout_ms` and keeps the results for
  // the next Flush. Fails on a null-evaluation result the run does not
  // score (the other results are kept).
  Status Serve(Dispatcher* dispatcher, int timeout_ms);
  // Commits the results received so far and acknowledges them to their
  // workers.
  Status Flush(Dispatcher* dispatcher);

  lineage::Store* store_;
  RunSettings settings_;
  int64_t run_id_;
  LogSink log_;
  bool finished_ = false;
  bool score_null_evaluations_ = false;
  std::vector<lineage::Evaluation> unsaved_;  // Results not yet committed.
  // Offspring of the latest generation whose results are not committed
  // (ids awaited_first_ + i with awaited_[i] set; awaited_left_ of them):
  // until none is left, Run does not ask the store whether the generation
  // is complete (unless nothing at all is pending). A hint only; the
  // store decides.
  uint64_t awaited_first_ = 0;
  std::vector<bool> awaited_;
  size_t awaited_left_ = 0;
  // Genomes by id, ids increasing.
  struct GenomesById {
    std::vector<uint64_t> ids;
    std::vector<Genome> genomes;
    const Genome* Find(uint64_t id) const;
  };
  // The genomes of generation genomes_generation_'s members as this process
  // made them (the store holds the same), so the next generation is made
  // without reading them back; -1 when there are none.
  GenomesById genomes_;
  int genomes_generation_ = -1;
  // Until the initial population is chosen: the scores of the random
  // candidates made so far (ids 0, 1, ...) as committed to the store, read
  // from it once and then kept in step by Flush and AdvanceInitial, so
  // choosing does not read every candidate back at every commit.
  std::vector<lineage::Score> candidates_;
  bool candidates_loaded_ = false;
  int64_t evaluations_ = 0;
  const Clock* clock_ = &RealClock();  // The dispatcher's, once Run starts.
  double started_ = 0;                 // Seconds, clock_.
  double last_served_ = 0;             // When Serve last polled the dispatcher.
  double last_report_ = 0;             // When the last generation completed.
  int64_t evaluations_at_last_report_ = 0;
};

}  // namespace animat

#endif  // ANIMAT_MASTER_RUN_EVOLUTION_RUN_H_
