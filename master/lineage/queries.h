// The questions users ask of a lineage store, answered for one run: the
// best individual, the ancestors of an individual, and the whole phylogeny
// in the ALife data standard's CSV (id, ancestor_list, origin_time, ...).
//
// Read-only; any number may run while a master writes (WAL).
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
};

// The run's id: `run` if given, else the latest run. kNotFound if none.
Result<int64_t> ChooseRun(Store& store, std::optional<int64_t> run);

// The individual with the highest fitness (ties: the lowest id), with its
// body.
Result<Summary> Best(Store& store, int64_t run);

// Every ancestor of `id` (parents, their parents, ...), each once with its
// shortest distance, nearest first, then by id. kNotFound for an unknown id.
Result<std::vector<Summary>> Ancestors(Store& store, int64_t run, uint64_t id);

// Writes the run's phylogeny as ALife-standard CSV: columns id,
// ancestor_list ("[3,5]", or "[NONE]" for a random genome), origin_time
// (the generation it was made for), fitness (empty when none), status,
// operators. One row per individual, in increasing id.
Status ExportAlife(Store& store, int64_t run, std::ostream& out);

}  // namespace animat::lineage

#endif  // ANIMAT_MASTER_LINEAGE_QUERIES_H_
