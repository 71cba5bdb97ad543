#include "cli/load.h"

#include "animat/v1/genome.pb.h"
#include "common/genome/genome_proto.h"
#include "common/io/proto_file.h"

namespace animat::cli {

Result<Genome> LoadGenome(const std::string& path) {
  v1::Genome message;
  Status status = ReadProtoFile(path, &message);
  if (!status.ok()) return status;
  // An empty file parses (text and binary formats) as a genome without
  // elements, as "{}" does: neither is a genome anyone meant.
  if (message.elements_size() == 0) {
    return Status::InvalidArgument(
        path + ": no elements; a genome file lists at least one");
  }
  Result<Genome> genome = GenomeFromProto(message);
  if (!genome.ok()) return genome.status().WithPrefix(path);
  return genome;
}

Result<ModelConfig> LoadConfig(const std::string& path) {
  if (path.empty()) return ModelConfig{};
  return ReadConfigFile(path);
}

}  // namespace animat::cli
