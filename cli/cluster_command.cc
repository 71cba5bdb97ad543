// animat cluster (--db FILE... [--top N] | --genome FILE... [--config FILE...])
//   [--clusters K] [--every K] [-o FILE] [--svg FILE.svg] [--title TEXT]
//
// Clusters the strategy features of a set of animats without their labels
// and says how well the clusters agree with the labels (adjusted Rand
// index), as a table; with -o an animat.v1.StrategyClustering, with --svg
// the animats on their first two principal components (docs/analysis.md,
// "Clusters"). The animats are the N fittest distinct phenotypes (by state
// hash) of the last completed generation of each store's latest run,
// simulated under the run's model, or the genomes given, each under its
// configuration (one for all, or one each). An animat that cannot be
// analysed (it does not develop, or does not move) is left out, with a
// line on standard error.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "analysis/analyze.h"
#include "analysis/strategy_clusters.h"
#include "cli/animat_source.h"
#include "cli/commands.h"
#include "common/io/proto_file.h"
#include "figures/cluster_plot.h"
#include "master/lineage/queries.h"
#include "master/lineage/store.h"

namespace animat::cli {
namespace {

struct Options {
  std::vector<std::string> dbs;
  int top = 5;
  std::vector<std::string> genomes;
  std::vector<std::string> configs;
  std::optional<int> clusters;
  int every = 1;
  std::string output;
  bool output_given = false;
  std::string svg;
  bool svg_given = false;
  std::string title;
};

// An animat to analyse and what to call it.
struct Entry {
  std::string name;
  AnimatSource source;
};

// "dn1-seed2-129969" for a genome ".../dn1-seed2-129969.json", or the
// configuration's name without ".config" when each genome has its own
// ("guidance-seed1-353538.untrained").
std::string EntryName(const std::string& genome, const std::string& config) {
  if (config.empty()) return std::filesystem::path(genome).stem().string();
  std::string stem = std::filesystem::path(config).stem().string();
  const std::string suffix = ".config";
  if (stem.size() > suffix.size() &&
      stem.compare(stem.size() - suffix.size(), suffix.size(), suffix) == 0) {
    stem.resize(stem.size() - suffix.size());
  }
  return stem;
}

Result<std::vector<Entry>> StoreEntries(const Options& o) {
  std::vector<Entry> entries;
  for (const std::string& db : o.dbs) {
    Result<std::unique_ptr<lineage::Store>> store =
        lineage::Store::OpenForQueries(db);
    if (!store.ok()) return store.status();
    Result<int64_t> run = lineage::ChooseRun(**store, std::nullopt);
    if (!run.ok()) return run.status();
    Result<std::vector<lineage::Phenotype>> top =
        lineage::TopDistinctPhenotypes(**store, *run, o.top);
    if (!top.ok()) return top.status();
    const std::string stem = std::filesystem::path(db).stem().string();
    for (const lineage::Phenotype& p : *top) {
      Entry e;
      e.name = stem + " #" + std::to_string(p.id);
      e.source.db = db;
      e.source.individual = p.id;
      e.source.run = *run;
      e.source.every = o.every;
      entries.push_back(e);
    }
  }
  return entries;
}

Result<std::vector<Entry>> GenomeEntries(const Options& o) {
  const bool each = o.configs.size() > 1;
  if (each && o.configs.size() != o.genomes.size()) {
    return Status::InvalidArgument(
        "give one --config for all genomes or one per --genome (" +
        std::to_string(o.genomes.size()) + " genomes, " +
        std::to_string(o.configs.size()) + " configurations)");
  }
  std::vector<Entry> entries;
  for (size_t i = 0; i < o.genomes.size(); ++i) {
    Entry e;
    e.source.genome = o.genomes[i];
    if (!o.configs.empty()) e.source.config = o.configs[each ? i : 0];
    e.source.every = o.every;
    e.name = EntryName(o.genomes[i], each ? o.configs[i] : "");
    entries.push_back(e);
  }
  return entries;
}

// Simulates and analyses one animat (the default window).
Result<analysis::LabelledAnimat> Analyse(const Entry& e) {
  Result<v1::Trace> trace = LoadAnimatTrace(e.source);
  if (!trace.ok()) return trace.status().WithPrefix(e.name);
  Result<analysis::Recording> recording = analysis::RecordingFromTrace(*trace);
  if (!recording.ok()) return recording.status().WithPrefix(e.name);
  Result<analysis::Analysis> a = analysis::Analyze(*recording, {});
  if (!a.ok()) return a.status().WithPrefix(e.name);
  analysis::LabelledAnimat out;
  out.name = e.name;
  out.strategy = a->strategy;
  if (trace->result().has_fitness()) out.fitness = trace->result().fitness();
  return out;
}

std::string DefaultTitle(const analysis::StrategyClustering& c) {
  char agreement[32];
  std::snprintf(agreement, sizeof(agreement), "%.2f", c.agreement);
  return "Strategy features of " + std::to_string(c.animats.size()) +
         " animats: " + std::to_string(c.clusters) +
         " Ward clusters (colour) against the labels (shape); adjusted Rand "
         "index " +
         agreement;
}

Status Write(const Options& o, const analysis::StrategyClustering& c) {
  if (o.output_given) {
    Status status =
        WriteProtoFile(o.output, analysis::StrategyClusteringToProto(c));
    if (!status.ok()) return status;
  }
  if (o.svg_given) {
    const std::string title = o.title.empty() ? DefaultTitle(c) : o.title;
    Status status = WriteFile(o.svg, figures::ClusterPlotSvg(c, title));
    if (!status.ok()) return status;
  }
  return Status::Ok();
}

int Run(const Options& o) {
  if (o.dbs.empty() == o.genomes.empty()) {
    return Fail("give --db FILE (one or more) or --genome FILE (one or more)");
  }
  if (!o.dbs.empty() && !o.configs.empty()) {
    return Fail("--config goes with --genome; a store's runs have their own");
  }
  if (o.svg_given && !o.svg.ends_with(".svg")) {
    return Fail(o.svg + ": the figure is SVG; name it .svg");
  }
  if (o.output_given) {
    Result<ProtoFormat> format = ProtoFormatForPath(o.output);
    if (!format.ok()) return Fail(format.status().message());
  }
  Result<std::vector<Entry>> entries =
      o.dbs.empty() ? GenomeEntries(o) : StoreEntries(o);
  if (!entries.ok()) return Fail(entries.status().message());
  // An animat that cannot be analysed (one that does not move) is left
  // out, saying so.
  std::vector<analysis::LabelledAnimat> animats;
  for (const Entry& e : *entries) {
    Result<analysis::LabelledAnimat> a = Analyse(e);
    if (!a.ok()) {
      std::fprintf(stderr, "animat: left out %s\n",
                   a.status().message().c_str());
      continue;
    }
    animats.push_back(std::move(a).value());
  }
  if (animats.empty()) return Fail("no animat could be analysed");
  const analysis::StrategyClustering c =
      analysis::ClusterStrategies(animats, o.clusters);
  std::fputs(analysis::StrategyClusteringSummary(c).c_str(), stdout);
  Status status = Write(o, c);
  if (!status.ok()) return Fail(status.message());
  return 0;
}

}  // namespace

Command AddClusterCommand(CLI::App& app) {
  auto o = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "cluster",
      "Cluster the strategy features of animats without their labels and "
      "compare clusters and labels (docs/analysis.md, Clusters)");
  sub->add_option("--db", o->dbs,
                  "Lineage stores: the --top fittest distinct phenotypes of "
                  "each latest run's last completed generation");
  sub->add_option("--top", o->top, "Phenotypes per store")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  sub->add_option("--genome", o->genomes, "Genome files instead of stores");
  sub->add_option("--config", o->configs,
                  "Configuration for every --genome, or one per --genome in "
                  "order (default: docs/model.md's)");
  sub->add_option("--clusters", o->clusters,
                  "Clusters to cut (default: the largest gap in Ward's "
                  "merge heights, 2 to 8)")
      ->check(CLI::Range(1, 1000));
  sub->add_option("--every", o->every,
                  "Record every K-th motion step when simulating")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  CLI::Option* output =
      sub->add_option("-o,--output", o->output,
                      "Write animat.v1.StrategyClustering (.json, .txtpb)");
  CLI::Option* svg =
      sub->add_option("--svg", o->svg, "Draw the clusters (.svg)");
  sub->add_option("--title", o->title, "The figure's title");
  return [o, output, svg] {
    o->output_given = output->count() > 0;
    o->svg_given = svg->count() > 0;
    return Run(*o);
  };
}

}  // namespace animat::cli
