#include "cli/load.h"

#include "animat/v1/genome.pb.h"
#include "common/genome/genome_proto.h"
#include "common/io/proto_file.h"

namespace animat::cli {

Result<Genome> LoadGenome(const std::string& path) {
  v1::Genome message;
  Status status = ReadProtoFile(path, &message);
  if (!status.ok()) return status;
  Result<Genome> genome = GenomeFromProto(message);
  if (!genome.ok()) return genome.status().WithPrefix(path);
  return genome;
}

Result<ModelConfig> LoadConfig(const std::string& path) {
  if (path.empty()) return ModelConfig{};
  return ReadConfigFile(path);
}

}  // namespace animat::cli
