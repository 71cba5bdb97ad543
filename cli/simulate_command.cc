// animat simulate --genome FILE [--config FILE] [--trace FILE] [--every K]
//                 [--trial K]
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/load.h"
#include "common/base/text.h"
#include "common/evaluation/evaluator.h"
#include "common/evaluation/trace_recorder.h"
#include "common/genome/genome_proto.h"
#include "common/io/proto_file.h"
#include "master/lineage/store.h"

namespace animat::cli {
namespace {

struct Options {
  std::string genome;
  std::string config;
  std::string trace;
  int every = 10;
  int trial = 0;
  bool json = false;
};

// One line of the result: its key and its value as text, quoted in JSON
// when it is a string.
struct Field {
  std::string key;
  std::string value;
  bool text = false;
};

// The shortest form that reads back to the same double.
std::string Exact(double value) { return ShortestDouble(value); }

// The result's fields in the order printed, named and written as the
// lineage store's columns are (docs/lineage.md, `evaluations`): the status
// in lowercase, the state hash as 16 hex digits, numbers as numbers.
std::vector<Field> ResultFields(const EvaluationResult& r) {
  std::vector<Field> fields;
  fields.push_back({"status", EvalStatusName(r.status), true});
  if (!r.reason.empty()) fields.push_back({"reason", r.reason, true});
  if (r.fitness) fields.push_back({"fitness", Exact(*r.fitness)});
  if (r.distance) fields.push_back({"distance", Exact(*r.distance)});
  if (r.energy) fields.push_back({"energy", Exact(*r.energy)});
  if (r.max_overlap) fields.push_back({"max_overlap", Exact(*r.max_overlap)});
  fields.push_back({"cells", std::to_string(r.cells)});
  fields.push_back({"steps", std::to_string(r.steps)});
  if (r.state_hash != 0) {
    fields.push_back({"state_hash", lineage::Hex64(r.state_hash), true});
  }
  if (!r.source_distances.empty()) {
    std::string list = "[";
    for (size_t k = 0; k < r.source_distances.size(); ++k) {
      list += (k > 0 ? ", " : "") + Exact(r.source_distances[k]);
    }
    fields.push_back({"source_distances", list + "]"});
  }
  if (r.body) {
    fields.push_back({"springs", std::to_string(r.body->springs)});
    fields.push_back({"chambers", std::to_string(r.body->chambers)});
    fields.push_back({"skin_edges", std::to_string(r.body->skin_edges)});
    fields.push_back({"spread_major", Exact(r.body->spread_major)});
    fields.push_back({"spread_minor", Exact(r.body->spread_minor)});
  }
  return fields;
}

std::string JsonString(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char escape[8];
      std::snprintf(escape, sizeof(escape), "\\u%04x", c);
      out += escape;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

void PrintResult(const EvaluationResult& r, bool json) {
  const std::vector<Field> fields = ResultFields(r);
  std::string out = json ? "{\n" : "";
  for (size_t i = 0; i < fields.size(); ++i) {
    const Field& f = fields[i];
    if (json) {
      out += "  \"" + f.key +
             "\": " + (f.text ? JsonString(f.value) : f.value) +
             (i + 1 < fields.size() ? ",\n" : "\n");
    } else {
      out += f.key + ": " + f.value + "\n";
    }
  }
  if (json) out += "}\n";
  std::fputs(out.c_str(), stdout);
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

  if (o.trial != 0 &&
      (!config->guidance.enabled || o.trial >= config->guidance.trials)) {
    return Fail("--trial " + std::to_string(o.trial) +
                (config->guidance.enabled
                     ? ": the configuration has " +
                           std::to_string(config->guidance.trials) +
                           " guidance trials (0 to " +
                           std::to_string(config->guidance.trials - 1) + ")"
                     : ": guidance is off in the configuration (one motion)"));
  }

  std::unique_ptr<TraceRecorder> recorder;
  if (!o.trace.empty()) {
    recorder = std::make_unique<TraceRecorder>(*config, o.every);
  }
  EvaluateOptions options;
  options.observed_trial = o.trial;
  const EvaluationResult result =
      Evaluate(*genome, *config, recorder.get(), options);

  if (recorder) {
    v1::Trace& trace = recorder->trace();
    *trace.mutable_config() = ConfigToProto(*config);
    *trace.mutable_genome() = GenomeToProto(*genome);
    *trace.mutable_result() = EvaluationResultToProto(result);
    Status status = WriteProtoFile(o.trace, trace);
    if (!status.ok()) return Fail(status.message());
  }
  PrintResult(result, o.json);
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
  sub->add_option("--trial", options->trial,
                  "With guidance (docs/model.md §10.2): the trial whose "
                  "motion the trace records")
      ->check(CLI::Range(0, kMaxGuidanceTrials - 1))
      ->capture_default_str();
  sub->add_flag("--json", options->json,
                "Print the result as one JSON object: the same keys and "
                "values as the text (docs/formats.md)");
  return [options] { return Run(*options); };
}

}  // namespace animat::cli
