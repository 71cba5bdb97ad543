#include "master/campaign/campaign_status.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <system_error>

#include "master/evolution/evolution_params.h"
#include "master/lineage/queries.h"
#include "master/lineage/store.h"

namespace animat {
namespace {

RunStatus ReadRun(const std::string& name, const std::string& path) {
  RunStatus status;
  status.name = name;
  status.state = "not started";
  std::error_code error;
  if (!std::filesystem::exists(path, error)) return status;
  const auto fail = [&status](const Status& why) {
    status.state = "unreadable: " + why.message();
    return status;
  };
  Result<std::unique_ptr<lineage::Store>> store =
      lineage::Store::OpenForQueries(path);
  if (!store.ok()) return fail(store.status());
  Result<std::vector<lineage::RunRow>> runs = (*store)->Runs();
  if (!runs.ok()) return fail(runs.status());
  if (runs->empty()) return status;
  const lineage::RunRow& run = runs->back();
  status.state = run.state == "finished" ? "finished" : "in progress";
  EvolutionParams params;
  Status read = EvolutionParamsFromProto(run.config.evolution(), &params);
  if (!read.ok()) return fail(read);
  Result<std::vector<lineage::CompletedGeneration>> done =
      lineage::CompletedGenerations(**store, run.run_id);
  if (!done.ok()) return fail(done.status());
  // A run that extends while improving: its length once it is decided.
  std::vector<std::optional<double>> bests;
  for (const lineage::CompletedGeneration& g : *done) {
    bests.push_back(g.stats.best);
  }
  status.generations = EvolutionLength(params, bests);
  if (!done->empty()) {
    // Generations are numbered from 0 (the initial population).
    status.generations_done = done->back().generation + 1;
    status.best = done->back().stats.best;
    status.mean = done->back().stats.mean;
  }
  return status;
}

std::string Number(const std::optional<double>& value) {
  if (!value) return "-";
  char text[32];
  std::snprintf(text, sizeof(text), "%.6g", *value);
  return text;
}

}  // namespace

Result<std::vector<RunStatus>> ReadCampaignStatus(
    const std::string& dir,
    const std::optional<std::vector<std::string>>& names) {
  std::vector<std::string> runs;
  if (names) {
    runs = *names;
  } else {
    std::error_code error;
    std::filesystem::directory_iterator it(dir, error);
    if (error) {
      return Status::NotFound(
          dir + ": cannot read the campaign's folder: " + error.message());
    }
    for (const auto& entry : it) {
      if (entry.path().extension() == ".db") {
        runs.push_back(entry.path().stem().string());
      }
    }
    std::sort(runs.begin(), runs.end());
  }
  std::vector<RunStatus> status;
  for (const std::string& name : runs) {
    status.push_back(
        ReadRun(name, (std::filesystem::path(dir) / (name + ".db")).string()));
  }
  return status;
}

std::string FormatCampaignStatus(const std::vector<RunStatus>& runs) {
  size_t width = 3;
  for (const RunStatus& r : runs) width = std::max(width, r.name.size());
  char line[512];
  std::string table;
  std::snprintf(line, sizeof(line), "%-*s  %-11s  %-12s  %-12s  %s\n",
                static_cast<int>(width), "run", "generation", "best", "mean",
                "state");
  table += line;
  int finished = 0;
  for (const RunStatus& r : runs) {
    const std::string generation =
        std::to_string(r.generations_done) + "/" +
        (r.generations > 0 ? std::to_string(r.generations) : "?");
    std::snprintf(line, sizeof(line), "%-*s  %-11s  %-12s  %-12s  %s\n",
                  static_cast<int>(width), r.name.c_str(), generation.c_str(),
                  Number(r.best).c_str(), Number(r.mean).c_str(),
                  r.state.c_str());
    table += line;
    finished += r.state == "finished";
  }
  table += std::to_string(finished) + " of " + std::to_string(runs.size()) +
           " runs finished\n";
  return table;
}

}  // namespace animat
