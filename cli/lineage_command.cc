// animat lineage best|ancestors ID|genome ID -o FILE|export --format alife
//   --db FILE [--run R]
// animat lineage configs --db FILE [--run R] [--generation G [-o FILE]]
// animat lineage upgrade --db FILE
//
// Questions about a lineage store (docs/lineage.md). Read-only: it can run
// while a master writes. `upgrade` brings a store written by an older
// animat to this build's schema (as a master of this build would), which
// the questions need.
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "cli/commands.h"
#include "common/base/text.h"
#include "common/io/proto_file.h"
#include "master/lineage/queries.h"
#include "master/lineage/schema.h"

namespace animat::cli {
namespace {

struct Options {
  std::string db;
  std::optional<int64_t> run;
  uint64_t id = 0;
  std::string output = "-";
  std::string format = "alife";
  std::optional<int> generation;
};

std::string FitnessText(const std::optional<double>& fitness) {
  if (!fitness) return "-";
  return ShortestDouble(*fitness);
}

// The body's lines, as `animat simulate` prints them (none for a store
// that did not record it).
void PrintBody(const v1::BodySummary& body) {
  std::printf(
      "cells: %d\nsprings: %d\nchambers: %d\nskin_edges: %d\n"
      "spread_major: %s\nspread_minor: %s\n",
      body.cells(), body.springs(), body.chambers(), body.skin_edges(),
      ShortestDouble(body.spread_major()).c_str(),
      ShortestDouble(body.spread_minor()).c_str());
}

template <typename Body>
int WithRun(const Options& o, Body body) {
  Result<std::unique_ptr<lineage::Store>> store =
      lineage::Store::OpenForQueries(o.db);
  if (!store.ok()) return Fail(store.status().message());
  Result<int64_t> run = lineage::ChooseRun(**store, o.run);
  if (!run.ok()) return Fail(run.status().message());
  return body(**store, *run);
}

int Best(const Options& o) {
  return WithRun(o, [&](lineage::Store& store, int64_t run) {
    Result<lineage::Summary> best = lineage::Best(store, run);
    if (!best.ok()) return Fail(best.status().message());
    std::printf("id: %llu\ngeneration: %d\nfitness: %s\noperators: %s\n",
                static_cast<unsigned long long>(best->id), best->generation,
                FitnessText(best->fitness).c_str(), best->operators.c_str());
    if (best->body) PrintBody(*best->body);
    if (best->swum)
      std::printf("distance: %s\n", ShortestDouble(*best->swum).c_str());
    if (best->energy)
      std::printf("energy: %s\n", ShortestDouble(*best->energy).c_str());
    if (best->max_overlap) {
      std::printf("max_overlap: %s\n",
                  ShortestDouble(*best->max_overlap).c_str());
    }
    if (!best->isa.empty()) std::printf("isa: %s\n", best->isa.c_str());
    if (!best->source_distances.empty()) {
      std::string list;
      for (double d : best->source_distances) {
        list += (list.empty() ? "" : ", ") + ShortestDouble(d);
      }
      std::printf("source_distances: [%s]\n", list.c_str());
    }
    return 0;
  });
}

int Ancestors(const Options& o) {
  return WithRun(o, [&](lineage::Store& store, int64_t run) {
    Result<std::vector<lineage::Summary>> ancestors =
        lineage::Ancestors(store, run, o.id);
    if (!ancestors.ok()) return Fail(ancestors.status().message());
    std::string csv = "distance,id,generation,fitness,status,operators\n";
    for (const lineage::Summary& a : *ancestors) {
      csv += std::to_string(a.distance) + "," + std::to_string(a.id) + "," +
             std::to_string(a.generation) + "," +
             (a.fitness ? FitnessText(a.fitness) : "") + "," + a.status +
             ",\"" + a.operators + "\"\n";
    }
    Status status = WriteFile(o.output, csv);
    if (!status.ok()) return Fail(status.message());
    return 0;
  });
}

int GenomeOf(const Options& o) {
  return WithRun(o, [&](lineage::Store& store, int64_t run) {
    Result<lineage::IndividualRow> row = store.Individual(run, o.id);
    if (!row.ok()) return Fail(row.status().message());
    Status status = WriteProtoFile(o.output, row->genome);
    if (!status.ok()) return Fail(status.message());
    return 0;
  });
}

int Export(const Options& o) {
  if (o.format != "alife") {
    return Fail("--format: only alife (the ALife data standard) is known");
  }
  return WithRun(o, [&](lineage::Store& store, int64_t run) {
    Status status;
    if (o.output == "-") {
      status = lineage::ExportAlife(store, run, std::cout);
    } else {
      std::ofstream out(o.output);
      if (!out) return Fail(o.output + ": cannot write");
      status = lineage::ExportAlife(store, run, out);
    }
    if (!status.ok()) return Fail(status.message());
    return 0;
  });
}

// The configuration history, one line a configuration; with --generation,
// the configuration in force at that generation, as a run configuration
// file (text format).
int Configs(const Options& o) {
  return WithRun(o, [&](lineage::Store& store, int64_t run) {
    Result<std::vector<lineage::RunConfigRow>> history =
        store.ConfigHistory(run);
    if (!history.ok()) return Fail(history.status().message());
    if (o.generation) {
      const lineage::RunConfigRow* in_force = nullptr;
      for (const lineage::RunConfigRow& row : *history) {
        if (row.from_generation <= *o.generation) in_force = &row;
      }
      if (in_force == nullptr) {
        return Fail("run " + std::to_string(run) +
                    " has no configuration recorded for generation " +
                    std::to_string(*o.generation));
      }
      // Standard output in text format, like `animat config defaults`.
      Status status = o.output == "-"
                          ? WriteFile("-", SerializeProto(in_force->config,
                                                          ProtoFormat::kText))
                          : WriteProtoFile(o.output, in_force->config);
      if (!status.ok()) return Fail(status.message());
      return 0;
    }
    for (const lineage::RunConfigRow& row : *history) {
      std::printf("%d: from generation %d, config %s, build \"%s\", %s: %s\n",
                  row.change, row.from_generation, row.config_hash.c_str(),
                  row.build_id.c_str(), row.recorded_at.c_str(),
                  row.reason.c_str());
    }
    return 0;
  });
}

int Upgrade(const Options& o) {
  Result<int> before = lineage::Store::Upgrade(o.db);
  if (!before.ok()) return Fail(before.status().message());
  if (*before == lineage::kSchemaVersion) {
    std::printf("%s: already at schema version %d\n", o.db.c_str(), *before);
  } else {
    std::printf("%s: upgraded from schema version %d to %d\n", o.db.c_str(),
                *before, lineage::kSchemaVersion);
  }
  return 0;
}

}  // namespace

Command AddLineageCommand(CLI::App& app) {
  auto o = std::make_shared<Options>();
  CLI::App* lineage = app.add_subcommand(
      "lineage", "Ask a lineage store about a run (docs/lineage.md)");
  lineage->require_subcommand(1);
  auto common = [&](CLI::App* sub) {
    sub->add_option("--db", o->db, "The lineage store")->required();
    sub->add_option("--run", o->run, "Which run (default: the latest)")
        ->check(IdValidator(kMaxRunId));
  };
  CLI::App* best = lineage->add_subcommand(
      "best", "The individual with the highest fitness");
  common(best);
  CLI::App* ancestors = lineage->add_subcommand(
      "ancestors", "Every ancestor of an individual, nearest first (CSV)");
  common(ancestors);
  ancestors->add_option("id", o->id, "The individual")
      ->required()
      ->check(IdValidator());
  ancestors
      ->add_option("-o,--output", o->output,
                   "Output file; - for standard output")
      ->capture_default_str();
  CLI::App* genome = lineage->add_subcommand(
      "genome", "Write an individual's genome (for animat simulate)");
  common(genome);
  genome->add_option("id", o->id, "The individual")
      ->required()
      ->check(IdValidator());
  genome
      ->add_option("-o,--output", o->output,
                   "Output file: .json, .txtpb or .binpb; - for JSON")
      ->required();
  CLI::App* export_command = lineage->add_subcommand(
      "export", "The whole phylogeny as ALife-standard CSV");
  common(export_command);
  export_command->add_option("--format", o->format, "alife")
      ->capture_default_str();
  export_command
      ->add_option("-o,--output", o->output,
                   "Output file; - for standard output")
      ->capture_default_str();
  CLI::App* configs = lineage->add_subcommand(
      "configs",
      "The run's configurations, from which generation each (--force and "
      "extensions change them); with --generation, the one in force then");
  common(configs);
  CLI::Option* generation =
      configs
          ->add_option("--generation", o->generation,
                       "Write the configuration in force at this generation")
          ->check(CLI::Range(0, 100000000));
  configs
      ->add_option("-o,--output", o->output,
                   "With --generation: output file (.txtpb or .json); - for "
                   "standard output (text format)")
      ->capture_default_str()
      ->needs(generation);
  CLI::App* upgrade = lineage->add_subcommand(
      "upgrade",
      "Bring a store written by an older animat to this build's schema");
  upgrade->add_option("--db", o->db, "The lineage store")->required();
  return [o, best, ancestors, genome, configs, upgrade] {
    if (upgrade->parsed()) return Upgrade(*o);
    if (configs->parsed()) return Configs(*o);
    if (best->parsed()) return Best(*o);
    if (ancestors->parsed()) return Ancestors(*o);
    if (genome->parsed()) return GenomeOf(*o);
    return Export(*o);
  };
}

}  // namespace animat::cli
