// A run record: what the reports need from one finished run whose lineage
// store is not kept, written by scripts/run_record.py as
// DIR/record.json (docs/results/runs/README.md). This reads the part the
// figures draw: the run's name, seed, configuration and per-generation
// fitness statistics.
#ifndef ANIMAT_CLI_RUN_RECORD_H_
#define ANIMAT_CLI_RUN_RECORD_H_

#include <cstdint>
#include <string>
#include <vector>

#include "animat/v1/config.pb.h"
#include "common/base/status.h"
#include "master/lineage/queries.h"

namespace animat::cli {

struct RunRecord {
  std::string run;  // The record's name, e.g. "v3-dn1-seed1".
  int64_t seed = 0;
  v1::RunConfig config;  // Parsed from the record's `config_text`.
  // Each completed generation's statistics, in increasing generation; a
  // statistic the record holds as null (no ok member) is empty.
  std::vector<lineage::CompletedGeneration> generations;
};

// Reads `path`: a record's folder (its record.json is read) or the
// record.json itself. kNotFound or kIoError when it cannot be read;
// kInvalidArgument, naming the file and the field, when it is not JSON,
// lacks a field, holds one of the wrong type or a non-finite or
// non-integral number where an integer belongs, or its generations are not
// increasing. Thread-safe (no shared state).
Result<RunRecord> ReadRunRecord(const std::string& path);

}  // namespace animat::cli

#endif  // ANIMAT_CLI_RUN_RECORD_H_
