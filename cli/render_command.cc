// animat render (--genome FILE | --db FILE --individual ID [--run R] |
//   --trace FILE) [--config FILE] [--every K] -o PAGE.html
//
// One self-contained HTML page replaying development and motion
// (viz/page.h). A genome, or an individual of a lineage store (under its
// run's configuration unless --config says otherwise), is simulated here;
// a trace written by `simulate --trace` or `scene --trace` is shown as is.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "cli/commands.h"
#include "cli/load.h"
#include "common/base/text.h"
#include "common/evaluation/evaluator.h"
#include "common/evaluation/trace_recorder.h"
#include "common/genome/genome_proto.h"
#include "common/io/proto_file.h"
#include "master/lineage/queries.h"
#include "viz/page.h"

namespace animat::cli {
namespace {

struct Options {
  std::string genome;
  std::string db;
  std::optional<uint64_t> individual;
  std::optional<int64_t> run;
  std::string trace;
  std::string config;
  int every = 5;
  double neutral_rate = viz::kDefaultNeutralRate;
  std::string output;
};

// The name of the file at `path`, without its folders: the page's title.
std::string FileName(const std::string& path) {
  const std::string name = std::filesystem::path(path).filename().string();
  return name.empty() ? path : name;
}

// Simulates `genome` under `config`, recording every `every`-th step.
v1::Trace Simulate(const Genome& genome, const ModelConfig& config, int every) {
  TraceRecorder recorder(config, every);
  const EvaluationResult result = Evaluate(genome, config, &recorder);
  v1::Trace trace = std::move(recorder.trace());
  *trace.mutable_config() = ConfigToProto(config);
  *trace.mutable_genome() = GenomeToProto(genome);
  *trace.mutable_result() = EvaluationResultToProto(result);
  return trace;
}

// The trace of an individual of a lineage store, and a title naming it.
Result<v1::Trace> FromStore(const Options& o, std::string* title) {
  Result<std::unique_ptr<lineage::Store>> store =
      lineage::Store::OpenForQueries(o.db);
  if (!store.ok()) return store.status();
  Result<int64_t> run = lineage::ChooseRun(**store, o.run);
  if (!run.ok()) return run.status().WithPrefix(o.db);
  Result<lineage::IndividualRow> row =
      (*store)->Individual(*run, *o.individual);
  if (!row.ok()) return row.status().WithPrefix(o.db);
  const std::string name = "individual " + std::to_string(row->id) +
                           " of run " + std::to_string(*run);
  Result<Genome> genome = GenomeFromProto(row->genome);
  if (!genome.ok()) return genome.status().WithPrefix(o.db + ": " + name);

  ModelConfig config;
  if (!o.config.empty()) {
    Result<ModelConfig> read = LoadConfig(o.config);
    if (!read.ok()) return read.status();
    config = *read;
  } else {
    Result<std::vector<lineage::RunRow>> runs = (*store)->Runs();
    if (!runs.ok()) return runs.status().WithPrefix(o.db);
    for (const lineage::RunRow& r : *runs) {
      if (r.run_id != *run) continue;
      Status status = ConfigFromProto(r.config.model(), &config);
      if (!status.ok()) {
        return status.WithPrefix(o.db + ": run " + std::to_string(*run) +
                                 " configuration");
      }
    }
  }

  v1::Trace trace = Simulate(*genome, config, o.every);
  // The store's fitness came from the same genome and configuration; a
  // different one means another simulator build evaluated it.
  if (row->fitness && trace.result().has_fitness() &&
      *row->fitness != trace.result().fitness()) {
    std::fprintf(stderr,
                 "animat: note: the store's fitness of %s is %s, this "
                 "build gives %s\n",
                 name.c_str(), ShortestDouble(*row->fitness).c_str(),
                 ShortestDouble(trace.result().fitness()).c_str());
  }
  *title = name + " (generation " + std::to_string(row->generation) + ") of " +
           FileName(o.db);
  return trace;
}

int Run(const Options& o) {
  std::string title;
  v1::Trace trace;
  if (!o.trace.empty()) {
    Status status = ReadProtoFile(o.trace, &trace);
    if (!status.ok()) return Fail(status.message());
    title = FileName(o.trace);
  } else if (!o.db.empty()) {
    Result<v1::Trace> read = FromStore(o, &title);
    if (!read.ok()) return Fail(read.status().message());
    trace = std::move(*read);
  } else {
    Result<Genome> genome = LoadGenome(o.genome);
    if (!genome.ok()) return Fail(genome.status().message());
    Result<ModelConfig> config = LoadConfig(o.config);
    if (!config.ok()) return Fail(config.status().message());
    trace = Simulate(*genome, *config, o.every);
    title = FileName(o.genome);
  }

  viz::PageOptions page_options;
  page_options.title = title;
  page_options.neutral_rate = o.neutral_rate;
  Result<std::string> page = viz::RenderPage(trace, page_options);
  if (!page.ok()) {
    const std::string source = !o.trace.empty()    ? o.trace
                               : !o.genome.empty() ? o.genome
                                                   : title;
    return Fail(page.status().WithPrefix(source).message());
  }
  Status status = WriteFile(o.output, *page);
  if (!status.ok()) return Fail(status.message());
  if (o.output != "-") {
    std::printf("%s: %d development snapshots, %d motion frames, %zu kB\n",
                o.output.c_str(), trace.development_size(), trace.frames_size(),
                (page->size() + 1023) / 1024);
  }
  return 0;
}

}  // namespace

Command AddRenderCommand(CLI::App& app) {
  auto o = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "render",
      "Write one self-contained HTML page replaying an animat's development "
      "and motion (docs/formats.md)");
  // Exactly one source.
  CLI::Option_group* source = sub->add_option_group(
      "source", "What to show: one of --genome, --db, --trace");
  source->add_option("--genome", o->genome, "Genome file (.json, .txtpb)");
  CLI::Option* db =
      source->add_option("--db", o->db, "A lineage store (with --individual)");
  CLI::Option* trace = source->add_option(
      "--trace", o->trace, "A trace of animat simulate or scene, shown as is");
  source->require_option(1);
  CLI::Option* individual = sub->add_option("--individual", o->individual,
                                            "The individual of --db to show")
                                ->check(IdValidator())
                                ->needs(db);
  db->needs(individual);
  sub->add_option("--run", o->run, "The run of --db (default: the latest)")
      ->check(IdValidator(kMaxRunId))
      ->needs(db);
  sub->add_option("--config", o->config,
                  "Configuration file (default: docs/model.md's, or the run's "
                  "for --db)")
      ->excludes(trace);
  sub->add_option("--every", o->every,
                  "Record every K-th development and motion step (first and "
                  "last always)")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str()
      ->excludes(trace);
  sub->add_option("--neutral-rate", o->neutral_rate,
                  "Cells whose e - c changes by less than this per step are "
                  "drawn neutral (green)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  sub->add_option("-o,--output", o->output, "The page (.html); - for stdout")
      ->required();
  return [o] { return Run(*o); };
}

}  // namespace animat::cli
