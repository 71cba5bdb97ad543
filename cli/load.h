// Loading the inputs every command shares.
#ifndef ANIMAT_CLI_LOAD_H_
#define ANIMAT_CLI_LOAD_H_

#include <string>

#include "common/base/status.h"
#include "common/evaluation/model_config.h"
#include "common/genome/genome.h"

namespace animat::cli {

// Reads and validates a genome file; errors name the file and field. A
// file without elements (empty, or "{}") is refused.
Result<Genome> LoadGenome(const std::string& path);
// The defaults when `path` is empty, else the file over the defaults.
Result<ModelConfig> LoadConfig(const std::string& path);

}  // namespace animat::cli

#endif  // ANIMAT_CLI_LOAD_H_
