// animat simulate --genome FILE [--config FILE] [--trace FILE] [--every K]
#include <cinttypes>
#include <cstdio>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "cli/load.h"
#include "common/evaluation/evaluator.h"
#include "common/evaluation/trace_recorder.h"
#include "common/genome/genome_proto.h"
#include "common/io/proto_file.h"

namespace animat::cli {
namespace {

struct Options {
  std::string genome;
  std::string config;
  std::string trace;
  int every = 10;
  bool json = false;
};

void PrintResult(const EvaluationResult& r) {
  std::printf("status: %s\n", EvalStatusName(r.status));
  if (!r.reason.empty()) std::printf("reason: %s\n", r.reason.c_str());
  if (r.fitness) std::printf("fitness: %.17g\n", *r.fitness);
  std::printf("cells: %d\n", r.cells);
  std::printf("steps: %" PRId64 "\n", r.steps);
  if (r.state_hash != 0) {
    std::printf("state_hash: %016" PRIx64 "\n", r.state_hash);
  }
  if (r.body) {
    std::printf(
        "springs: %d\nchambers: %d\nskin_edges: %d\nspread_major: %.17g\n"
        "spread_minor: %.17g\n",
        r.body->springs, r.body->chambers, r.body->skin_edges,
        r.body->spread_major, r.body->spread_minor);
  }
}

int Run(const Options& o) {
  Result<Genome> genome = LoadGenome(o.genome);
  if (!genome.ok()) return Fail(genome.status().message());
  Result<ModelConfig> config = LoadConfig(o.config);
  if (!config.ok()) return Fail(config.status().message());
  if (!o.trace.empty()) {
    // Fail before the work if the trace path has no known format.
    Result<ProtoFormat> format = ProtoFormatForPath(o.trace);
    if (!format.ok()) return Fail(format.status().message());
  }

  std::unique_ptr<TraceRecorder> recorder;
  if (!o.trace.empty()) {
    recorder = std::make_unique<TraceRecorder>(*config, o.every);
  }
  const EvaluationResult result = Evaluate(*genome, *config, recorder.get());

  if (recorder) {
    v1::Trace& trace = recorder->trace();
    *trace.mutable_config() = ConfigToProto(*config);
    *trace.mutable_genome() = GenomeToProto(*genome);
    *trace.mutable_result() = EvaluationResultToProto(result);
    Status status = WriteProtoFile(o.trace, trace);
    if (!status.ok()) return Fail(status.message());
  }
  if (o.json) {
    std::fputs(
        SerializeProto(EvaluationResultToProto(result), ProtoFormat::kJson)
            .c_str(),
        stdout);
    std::fputs("\n", stdout);
  } else {
    PrintResult(result);
  }
  return 0;
}

}  // namespace

Command AddSimulateCommand(CLI::App& app) {
  auto options = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "simulate",
      "Develop and simulate an animat and print its status and fitness "
      "(exit 0 whatever the status; 1 on bad input)");
  sub->add_option("--genome", options->genome, "Genome file (.json, .txtpb)")
      ->required();
  sub->add_option("--config", options->config,
                  "Configuration file (defaults: docs/model.md)");
  sub->add_option("--trace", options->trace,
                  "Write a trace: config, development snapshots, body, "
                  "motion frames and result (.json, .txtpb, .binpb)");
  sub->add_option("--every", options->every,
                  "Trace every K-th development and motion step (first and "
                  "last always)")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  sub->add_flag("--json", options->json,
                "Print the result as JSON (animat.v1.EvaluationResult)");
  return [options] { return Run(*options); };
}

}  // namespace animat::cli
