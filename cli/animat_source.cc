#include "cli/animat_source.h"

#include <memory>

#include "cli/commands.h"
#include "cli/load.h"
#include "common/evaluation/evaluator.h"
#include "common/evaluation/trace_recorder.h"
#include "common/genome/genome_proto.h"
#include "common/io/proto_file.h"
#include "master/lineage/queries.h"
#include "master/lineage/store.h"

namespace animat::cli {
namespace {

v1::Trace Simulate(const Genome& genome, const ModelConfig& config, int every) {
  TraceRecorder recorder(config, every);
  const EvaluationResult result = Evaluate(genome, config, &recorder);
  v1::Trace& trace = recorder.trace();
  *trace.mutable_config() = ConfigToProto(config);
  *trace.mutable_genome() = GenomeToProto(genome);
  *trace.mutable_result() = EvaluationResultToProto(result);
  return std::move(trace);
}

}  // namespace

void AddAnimatSourceOptions(CLI::App* sub, AnimatSource* source) {
  sub->add_option("--genome", source->genome,
                  "Genome file (.json, .txtpb) to develop and simulate");
  sub->add_option("--config", source->config,
                  "Configuration file (default: docs/model.md's for --genome, "
                  "the run's for --db)");
  sub->add_option("--db", source->db, "Lineage store holding --individual");
  sub->add_option("--individual", source->individual, "Individual id in --db")
      ->check(IdValidator());
  sub->add_option("--run", source->run, "Run in --db (default: the latest)")
      ->check(IdValidator(kMaxRunId));
  sub->add_option("--trace", source->trace,
                  "A trace written by animat simulate --trace");
  sub->add_option("--every", source->every,
                  "Record every K-th motion step when simulating (1: the "
                  "paper's per-step activity)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
}

Result<ModelConfig> RunModelConfig(const std::string& db,
                                   std::optional<int64_t> run) {
  Result<std::unique_ptr<lineage::Store>> store =
      lineage::Store::OpenForQueries(db);
  if (!store.ok()) return store.status();
  Result<int64_t> run_id = lineage::ChooseRun(**store, run);
  if (!run_id.ok()) return run_id.status();
  Result<std::vector<lineage::RunRow>> runs = (*store)->Runs();
  if (!runs.ok()) return runs.status();
  for (const lineage::RunRow& row : *runs) {
    if (row.run_id != *run_id) continue;
    ModelConfig config;
    Status status = ConfigFromProto(row.config.model(), &config);
    if (!status.ok()) {
      return status.WithPrefix(db + ": run " + std::to_string(*run_id));
    }
    return config;
  }
  return Status::NotFound(db + ": no run " + std::to_string(*run_id));
}

namespace {

Status CheckOneSource(const AnimatSource& source) {
  const int given = (source.genome.empty() ? 0 : 1) +
                    (source.db.empty() ? 0 : 1) +
                    (source.trace.empty() ? 0 : 1);
  if (given != 1) {
    return Status::InvalidArgument(
        "give exactly one of --genome FILE, --db FILE --individual ID, "
        "--trace FILE");
  }
  return Status::Ok();
}

// --genome or --db: the genome and its configuration.
Result<AnimatModel> LoadStoredModel(const AnimatSource& source) {
  if (!source.genome.empty()) {
    Result<Genome> genome = LoadGenome(source.genome);
    if (!genome.ok()) return genome.status();
    Result<ModelConfig> config = LoadConfig(source.config);
    if (!config.ok()) return config.status();
    return AnimatModel{std::move(genome).value(), *config};
  }
  if (!source.individual) {
    return Status::InvalidArgument("--db needs --individual ID");
  }
  Result<ModelConfig> config = source.config.empty()
                                   ? RunModelConfig(source.db, source.run)
                                   : LoadConfig(source.config);
  if (!config.ok()) return config.status();
  Result<std::unique_ptr<lineage::Store>> store =
      lineage::Store::OpenForQueries(source.db);
  if (!store.ok()) return store.status();
  Result<int64_t> run = lineage::ChooseRun(**store, source.run);
  if (!run.ok()) return run.status();
  Result<lineage::IndividualRow> row =
      (*store)->Individual(*run, *source.individual);
  if (!row.ok()) return row.status();
  Result<Genome> genome = GenomeFromProto(row->genome);
  if (!genome.ok()) {
    return genome.status().WithPrefix(source.db + ": individual " +
                                      std::to_string(*source.individual));
  }
  return AnimatModel{std::move(genome).value(), *config};
}

}  // namespace

Result<AnimatModel> LoadAnimatModel(const AnimatSource& source) {
  Status status = CheckOneSource(source);
  if (!status.ok()) return status;
  if (source.trace.empty()) return LoadStoredModel(source);
  v1::Trace trace;
  status = ReadProtoFile(source.trace, &trace);
  if (!status.ok()) return status;
  AnimatModel model;
  status = ConfigFromProto(trace.config(), &model.config);
  if (!status.ok()) return status.WithPrefix(source.trace);
  Result<Genome> genome = GenomeFromProto(trace.genome());
  if (!genome.ok()) return genome.status().WithPrefix(source.trace);
  model.genome = std::move(genome).value();
  return model;
}

Result<v1::Trace> LoadAnimatTrace(const AnimatSource& source) {
  Status status = CheckOneSource(source);
  if (!status.ok()) return status;
  if (!source.trace.empty()) {
    v1::Trace trace;
    status = ReadProtoFile(source.trace, &trace);
    if (!status.ok()) return status;
    return trace;
  }
  Result<AnimatModel> model = LoadStoredModel(source);
  if (!model.ok()) return model.status();
  return Simulate(model->genome, model->config, source.every);
}

}  // namespace animat::cli
