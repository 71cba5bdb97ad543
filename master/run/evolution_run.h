// An evolutionary run driven through an evaluation service (the
// dispatcher) and recorded in a lineage store; started fresh or resumed
// exactly where it stopped. The run loop owns the flow: it serves the
// evaluators, commits results, and advances the run through its phases
// (initial_population.h, then a generation after another, whose offspring
// come from offspring_pipeline.h); neither the store nor the phases call
// back into the loop or the evaluators (docs/master.md).
//
// Determinism: every individual is a pure function of the run's seed, its
// id and the ranked generation before it (master/evolution/operators.h);
// ids are handed out in a fixed order, and the initial population is
// decided on evaluated candidates only (initial_population.h). So the
// store ends up with the same individuals, parents and evaluations
// whatever the number of workers, the order results arrive in, or how
// often the master was killed and resumed. An offspring whose genome is a
// parent generation member's is not submitted when the service's results
// follow the genome: it takes that member's evaluation, written with the
// generation (GenerationWrite::Reuse; docs/lineage.md).
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
#include "master/dispatch/evaluation_service.h"
#include "master/evolution/evolution_params.h"
#include "master/evolution/operators.h"
#include "master/lineage/store.h"
#include "master/run/initial_population.h"
#include "master/run/offspring_pipeline.h"
#include "master/run/run_plan.h"

namespace animat {

// One line's worth of progress, after each generation completes.
struct GenerationReport {
  int generation = 0;
  int generations = 0;  // Of the run.
  lineage::GenerationStats stats;
  int64_t evaluations = 0;  // Since this process started.
  double evaluations_per_second = 0;
  double seconds_left = -1;  // Estimate; -1 when unknown.
};

class EvolutionRun {
 public:
  // Carries out `plan` (made for `store`, run_plan.h): creates the run, or
  // updates its recorded configuration as planned. Refuses to record fewer
  // generations than the run has made (kInvalidArgument). The store must
  // outlive the run.
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

  // Serves `evaluators` (a Dispatcher built with model_config(), and with
  // acknowledge_on_receipt off so that workers keep each result until it
  // is committed) until the run has all its generations or `stop` becomes
  // true; results received so far are committed before returning.
  // `progress`, if set, is called after each generation completes. The run
  // keeps time (commit intervals, rates in the reports) by the evaluators'
  // clock. A result of a null-evaluation worker (nothing simulated) is
  // never recorded: Run fails, saying so.
  Status Run(
      EvaluationService* evaluators, const std::atomic<bool>& stop,
      const std::function<void(const GenerationReport&)>& progress = nullptr);

  const ModelConfig& model_config() const { return settings_.model; }
  const EvolutionParams& params() const { return settings_.evolution; }
  int64_t run_id() const { return run_id_; }
  bool finished() const { return finished_; }

 private:
  using Progress = std::function<void(const GenerationReport&)>;

  // Offspring of the latest generation whose results are not committed
  // (ids first + i with awaited[i] set; `left` of them): until none is
  // left, Run does not ask the store whether the generation is complete
  // (unless nothing at all is pending). A hint only; the store decides.
  struct AwaitedOffspring {
    uint64_t first = 0;
    std::vector<bool> awaited;
    size_t left = 0;
    void Expect(uint64_t first_id, size_t count);
    void Record(const std::vector<lineage::Evaluation>& committed);
    void Record(uint64_t id);
  };

  EvolutionRun(lineage::Store* store, RunSettings settings, int64_t run_id,
               LogSink log)
      : store_(store),
        settings_(std::move(settings)),
        run_id_(run_id),
        log_(std::move(log)) {}

  // Submits what was made and not evaluated before (a resumed run).
  Status SubmitUnevaluated(EvaluationService* evaluators);
  // Advances as far as the store allows: makes candidate blocks, chooses
  // the initial population, completes generations, makes the next one.
  // New individuals are submitted to `evaluators`.
  Status Advance(EvaluationService* evaluators, const Progress& progress);
  Status AdvanceInitial(EvaluationService* evaluators, bool* changed);
  // Marks the run finished (once).
  Status Finish(int generations);
  // How many generations the run makes (EvolutionLength), once generation
  // `completed` is complete: decided, from the store's statistics, when
  // the run has made params().generations, and logged then.
  Result<int> Length(int completed);
  // `scores`: of every member, all evaluated.
  Status CompleteGeneration(int generation,
                            const std::vector<lineage::Score>& scores,
                            const Progress& progress);
  void Report(int generation, const lineage::GenerationStats& stats,
              const Progress& progress);
  // `previous_scores`: of generation - 1's members, when at hand.
  Status MakeGeneration(int generation,
                        const std::vector<lineage::Score>* previous_scores,
                        EvaluationService* evaluators);
  // Generation `generation`'s parents: genomes_ made those of its members,
  // from this process's copy or the store, and their scores.
  Result<std::vector<Scored>> Parents(
      int generation, const std::vector<lineage::Score>* scores);
  // Writes the generation with the offspring `pipeline` makes, in chunks,
  // serving `evaluators` between chunks. An offspring whose evaluation key
  // (OffspringPipeline::KeyOf) is a key of `parents_by_key` (a parent
  // member's id by its genome's evaluation key) gets that member's
  // evaluation in the same transaction (GenerationWrite::Reuse) and its id
  // goes to `reused`; returns the offspring written that are still to be
  // evaluated.
  Result<std::vector<lineage::NewIndividual>> WriteGeneration(
      int generation, std::vector<uint64_t> members,
      OffspringPipeline* pipeline,
      const std::map<std::string, uint64_t>& parents_by_key,
      EvaluationService* evaluators, std::vector<uint64_t>* reused);
  // Polls `evaluators` for up to `timeout_ms` and keeps the results for
  // the next Flush. Fails on a null-evaluation result (the other results
  // are kept).
  Status Serve(EvaluationService* evaluators, int timeout_ms);
  // Commits the results received so far and acknowledges them.
  Status Flush(EvaluationService* evaluators);

  lineage::Store* store_;
  RunSettings settings_;
  int64_t run_id_;
  LogSink log_;
  bool finished_ = false;
  std::optional<int> length_;                 // Length's decision, once made.
  std::vector<lineage::Evaluation> unsaved_;  // Results not yet committed.
  AwaitedOffspring awaited_;
  // The genomes of generation genomes_generation_'s members as this process
  // made them (the store holds the same), so the next generation is made
  // without reading them back; -1 when there are none.
  GenomesById genomes_;
  int genomes_generation_ = -1;
  // Until the initial population is chosen (loaded when first needed).
  std::unique_ptr<InitialPopulation> initial_;
  int64_t evaluations_ = 0;
  const Clock* clock_ = &RealClock();  // The evaluators', once Run starts.
  double started_ = 0;                 // Seconds, clock_.
  double last_served_ = 0;             // When Serve last polled.
  double last_report_ = 0;             // When the last generation completed.
  int64_t evaluations_at_last_report_ = 0;
};

}  // namespace animat

#endif  // ANIMAT_MASTER_RUN_EVOLUTION_RUN_H_
