// The animat `analyze` and `figure` look at: a genome file, an individual
// of a lineage store, or a trace already written. Genomes are developed
// and simulated here, recording every `--every`-th motion step.
#ifndef ANIMAT_CLI_ANIMAT_SOURCE_H_
#define ANIMAT_CLI_ANIMAT_SOURCE_H_

#include <cstdint>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "animat/v1/trace.pb.h"
#include "common/base/status.h"
#include "common/evaluation/model_config.h"
#include "common/genome/genome.h"

namespace animat::cli {

struct AnimatSource {
  std::string genome;  // --genome FILE
  std::string config;  // --config FILE
  std::string db;      // --db FILE --individual ID [--run R]
  std::optional<uint64_t> individual;
  std::optional<int64_t> run;
  std::string trace;  // --trace FILE
  int every = 1;      // Steps between recorded frames when simulating.
};

// Registers --genome, --config, --db, --individual, --run, --trace and
// --every on `sub`.
void AddAnimatSourceOptions(CLI::App* sub, AnimatSource* source);

// The trace of the chosen animat: read from --trace, or made by
// evaluating the genome under --config, else the defaults (--genome) or
// the store run's own model configuration (--db). Errors name the file,
// store or individual; exactly one of --genome, --db and --trace must be
// given.
Result<v1::Trace> LoadAnimatTrace(const AnimatSource& source);

// The chosen animat's genome and model configuration, without simulating:
// from --genome and --config, the store's individual and run (or
// --config), or what a --trace records. Errors as LoadAnimatTrace's.
struct AnimatModel {
  Genome genome;
  ModelConfig config;
};
Result<AnimatModel> LoadAnimatModel(const AnimatSource& source);

// The model configuration a lineage store's run used.
Result<ModelConfig> RunModelConfig(const std::string& db,
                                   std::optional<int64_t> run);

}  // namespace animat::cli

#endif  // ANIMAT_CLI_ANIMAT_SOURCE_H_
