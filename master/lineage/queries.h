// The questions users ask of a lineage store, answered for one run: the
// best individual, the ancestors of an individual, the whole phylogeny in
// the ALife data standard's CSV (id, ancestor_list, origin_time, ...), the
// statistics of the completed generations, and the counts that say whether
// a run was recorded whole. The SQL behind them stays here: code outside
// master/lineage/ asks through these functions and Store's methods.
//
// Read-only; any number may run while a master writes (WAL). Like Store,
// not thread-safe: one thread uses a Store and these functions on it.
// Errors are Store's: SQLite failures as Status values naming the file.
#ifndef ANIMAT_MASTER_LINEAGE_QUERIES_H_
#define ANIMAT_MASTER_LINEAGE_QUERIES_H_

#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "animat/v1/trace.pb.h"
#include "common/base/status.h"
#include "master/lineage/store.h"

namespace animat::lineage {

struct Summary {
  uint64_t id = 0;
  int generation = 0;
  std::string operators;
  std::string status;
  std::optional<double> fitness;
  int distance = 0;  // Generations of descent, for ancestors.
  // Its body, when its evaluation built one and the store recorded it
  // (schema version 4 on); filled by Best only.
  std::optional<v1::BodySummary> body;
  // The distance swum (radii) and the actuators' work, when its evaluation
  // is ok and the store recorded them (schema version 6 on); filled by
  // Best only.
  std::optional<double> swum;
  std::optional<double> energy;
  // The deepest overlap of two unjoined cells (docs/model.md §8.6), when
  // its evaluation is ok and the store recorded it (schema version 8 on);
  // filled by Best only.
  std::optional<double> max_overlap;
  // The instruction-set path that evaluated it ("avx512", ...), when the
  // store recorded it (schema version 9 on); filled by Best only.
  std::string isa;
  // With active guidance, each trial's final distance to its source
  // (radii), in trial order (schema version 7 on); empty otherwise. Filled
  // by Best only.
  std::vector<double> source_distances;
};

// The run's id: `run` if given, else the latest run. kNotFound if none.
Result<int64_t> ChooseRun(Store& store, std::optional<int64_t> run);

// The individual with the highest fitness (ties: the lowest id), with its
// body.
Result<Summary> Best(Store& store, int64_t run);

// Every ancestor of `id` (parents, their parents, ...), each once with its
// shortest distance, nearest first, then by id. kNotFound for an unknown id.
Result<std::vector<Summary>> Ancestors(Store& store, int64_t run, uint64_t id);

// The scores of every individual of the run, in increasing id (no genomes
// are read).
Result<std::vector<Score>> Scores(Store& store, int64_t run);

// A completed generation's statistics, as CompleteGeneration recorded
// them.
struct CompletedGeneration {
  int generation = 0;
  GenerationStats stats;
};

// The run's completed generations, in increasing generation (none for a
// run that has completed none).
Result<std::vector<CompletedGeneration>> CompletedGenerations(Store& store,
                                                              int64_t run);

// One phenotype of a generation: its fittest member among those whose
// simulations are identical (the same `state_hash`), and how many members
// share it.
struct Phenotype {
  uint64_t id = 0;
  int generation = 0;  // The generation it is a member of.
  double fitness = 0;
  std::string state_hash;  // 16 hex digits.
  int members = 0;         // Members of the generation with this hash.
};

// The `count` fittest distinct phenotypes of the run's last completed
// generation: its members with status "ok", by fitness (ties: the lowest
// id), each state hash once, at its first member in that order (a member
// without a recorded hash is distinct). Fewer when
// the generation has fewer; kNotFound when the run has completed no
// generation.
Result<std::vector<Phenotype>> TopDistinctPhenotypes(Store& store, int64_t run,
                                                     int count);

// What the store holds of a run, counted, to check that a run was recorded
// whole (animat-master-bench does). Counts of individuals are of those
// made for the run, evaluated or not.
struct RunCounts {
  bool finished = false;     // The run's state is "finished".
  int64_t individuals = 0;   // Made.
  int64_t evaluated = 0;     // With an evaluation, of any status.
  int64_t ok = 0;            // With status "ok".
  int64_t with_fitness = 0;  // With a fitness.
  int64_t with_worker = 0;   // Evaluated by a named worker.
  int64_t with_evaluation_time = 0;
  int64_t with_genome = 0;  // A genome of at least one element.
  int64_t offspring = 0;    // Made for generation 1 or later.
  int64_t offspring_without_parents = 0;
  // Members of a generation, or offspring, not evaluated (only initial
  // candidates not chosen may be).
  int64_t needed_unevaluated = 0;
  int64_t generations = 0;           // Begun.
  int64_t complete_generations = 0;  // Completed.
  // The members with status "ok" of the completed generations, summed
  // (GenerationStats::evaluated).
  int64_t generations_evaluated = 0;
  int64_t members = 0;  // Of all generations.
  int64_t ranked_members = 0;
};

// The counts of run `run` (all zero, and not finished, for an unknown
// run).
Result<RunCounts> CountRun(Store& store, int64_t run);

// Writes the run's phylogeny as ALife-standard CSV: columns id,
// ancestor_list ("[3,5]", or "[NONE]" for a random genome), origin_time
// (the generation it was made for), fitness (empty when none), status,
// operators. One row per individual, in increasing id.
Status ExportAlife(Store& store, int64_t run, std::ostream& out);

}  // namespace animat::lineage

#endif  // ANIMAT_MASTER_LINEAGE_QUERIES_H_
