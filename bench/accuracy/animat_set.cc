#include "bench/accuracy/animat_set.h"

#include <algorithm>
#include <filesystem>
#include <system_error>

#include "animat/v1/config.pb.h"
#include "animat/v1/genome.pb.h"
#include "common/genome/genome_proto.h"
#include "common/io/proto_file.h"

namespace animat::accuracy {

namespace {

// A model file may set model constants only, not what the report compares.
Status CheckModelText(const std::string& path, const std::string& text) {
  v1::Config message;
  Status status = ParseProto(text, ProtoFormat::kText, &message);
  if (!status.ok()) return status.WithPrefix(path);
  const v1::PhysicsConfig& p = message.physics();
  const char* compared = p.has_integrator()         ? "physics.integrator"
                         : p.has_substeps()         ? "physics.substeps"
                         : p.has_contact_substeps() ? "physics.contact_substeps"
                         : p.has_contact_near()     ? "physics.contact_near"
                         : p.has_contact_inner_substeps()
                             ? "physics.contact_inner_substeps"
                         : p.has_drag_update()  ? "physics.drag_update"
                         : p.has_backend()      ? "physics.backend"
                         : p.has_contacts()     ? "physics.contacts"
                         : p.has_contact_rule() ? "physics.contact_rule"
                         : message.grn().has_precision() ? "grn.precision"
                                                         : nullptr;
  if (compared != nullptr) {
    return Status::InvalidArgument(path + ": " + compared +
                                   " is what the report compares; a model "
                                   "file may set model constants only");
  }
  ModelConfig config;
  status = ConfigFromProto(message, &config);
  if (!status.ok()) return status.WithPrefix(path);
  return Status::Ok();
}

}  // namespace

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
    Animat animat{name, *genome, IsEvolvedName(name), ""};
    fs::path model_path = path;
    model_path.replace_extension(".model.txtpb");
    if (fs::exists(model_path, error)) {
      Result<std::string> text = ReadFile(model_path.string());
      if (!text.ok()) return text.status();
      status = CheckModelText(model_path.string(), *text);
      if (!status.ok()) return status;
      animat.model_text = *text;
    }
    animats.push_back(std::move(animat));
  }
  return animats;
}

Result<ModelConfig> ForAnimat(const ModelConfig& config, const Animat& animat) {
  if (animat.model_text.empty()) return config;
  v1::Config message;
  Status status = ParseProto(animat.model_text, ProtoFormat::kText, &message);
  if (!status.ok()) return status.WithPrefix(animat.name);
  ModelConfig out = config;
  status = ConfigFromProto(message, &out);
  if (!status.ok()) return status.WithPrefix(animat.name);
  return out;
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
