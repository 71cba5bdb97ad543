#include "bench/accuracy/animat_set.h"

#include <algorithm>
#include <filesystem>
#include <system_error>

#include "animat/v1/genome.pb.h"
#include "common/genome/genome_proto.h"
#include "common/io/proto_file.h"

namespace animat::accuracy {

bool IsEvolvedName(const std::string& name) {
  return name.rfind("evolved-", 0) == 0;
}

Result<std::vector<Animat>> LoadAnimatSet(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code error;
  std::vector<fs::path> paths;
  for (fs::directory_iterator it(dir, error), end; !error && it != end;
       it.increment(error)) {
    if (it->is_regular_file() && it->path().extension() == ".json") {
      paths.push_back(it->path());
    }
  }
  if (error) {
    return Status::IoError(dir + ": cannot list: " + error.message());
  }
  if (paths.empty()) return Status::NotFound(dir + ": no *.json genomes");
  std::sort(paths.begin(), paths.end());

  std::vector<Animat> animats;
  for (const fs::path& path : paths) {
    v1::Genome message;
    Status status = ReadProtoFile(path.string(), &message);
    if (!status.ok()) return status;
    Result<Genome> genome = GenomeFromProto(message);
    if (!genome.ok()) return genome.status().WithPrefix(path.string());
    const std::string name = path.stem().string();
    animats.push_back({name, *genome, IsEvolvedName(name)});
  }
  return animats;
}

std::vector<Animat> QuickSubset(const std::vector<Animat>& animats, int random,
                                int evolved) {
  std::vector<Animat> subset;
  for (const Animat& animat : animats) {
    int& left = animat.evolved ? evolved : random;
    if (left <= 0) continue;
    --left;
    subset.push_back(animat);
  }
  return subset;
}

}  // namespace animat::accuracy
