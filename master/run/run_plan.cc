#include "master/run/run_plan.h"

#include "common/protocol/protocol.h"

namespace animat {

Result<RunPlan> PlanStart(lineage::Store* store, const RunSettings& settings) {
  Result<std::vector<lineage::RunRow>> runs = store->Runs();
  if (!runs.ok()) return runs.status();
  if (!runs->empty()) {
    return Status::InvalidArgument(
        store->path() +
        ": already holds a run; continue it with --resume, or use another "
        "database");
  }
  RunPlan plan;
  plan.settings = settings;
  return plan;
}

namespace {

// What differs between the settings given and the stored ones, and
// between this build and the run's, beyond the number of generations
// (which decides no individual).
std::vector<std::string> ResumeProblems(
    const std::optional<RunSettings>& settings, const RunSettings& stored,
    const lineage::RunRow& row) {
  const auto comparable = [](RunSettings s) {
    s.evolution.generations = 0;
    return protocol::MessageHash(RunSettingsToProto(s));
  };
  std::vector<std::string> problems;
  if (settings && comparable(*settings) != comparable(stored)) {
    problems.push_back("the configuration given differs from the run's");
  }
  if (row.build_id != protocol::BuildId()) {
    problems.push_back("the run was evaluated by build \"" + row.build_id +
                       "\", this is \"" + protocol::BuildId() +
                       "\" (results could differ in the last bits)");
  }
  return problems;
}

}  // namespace

Result<RunPlan> PlanResume(lineage::Store* store,
                           const std::optional<RunSettings>& settings,
                           bool force, std::optional<int> generations) {
  Result<std::vector<lineage::RunRow>> runs = store->Runs();
  if (!runs.ok()) return runs.status();
  if (runs->empty()) {
    return Status::NotFound(store->path() +
                            ": no run to resume; start one with --config");
  }
  const lineage::RunRow& row = runs->back();
  RunSettings stored;
  Status status = RunSettingsFromProto(row.config, &stored);
  if (!status.ok()) {
    return status.WithPrefix(store->path() + ": the stored configuration");
  }
  RunPlan plan;
  plan.run_id = row.run_id;
  plan.state = row.state;
  Result<std::optional<lineage::GenerationRow>> latest =
      store->LatestGenerationHead(row.run_id);
  if (!latest.ok()) return latest.status();
  plan.generations_made = *latest ? (*latest)->generation + 1 : 0;
  std::vector<std::string> problems = ResumeProblems(settings, stored, row);
  if (!problems.empty() && !force) {
    std::string message = store->path() + ": refusing to resume:";
    for (const std::string& p : problems) message += " " + p + ";";
    return Status::InvalidArgument(message + " --force resumes anyway");
  }
  plan.settings = settings && force ? *settings : stored;
  if (generations) plan.settings.evolution.generations = *generations;
  plan.update_config =
      plan.settings.evolution.generations != stored.evolution.generations ||
      !problems.empty();
  plan.forced = std::move(problems);
  return plan;
}

std::string ConfigChangeReason(const RunPlan& plan) {
  if (plan.forced.empty()) {
    return "generations set to " +
           std::to_string(plan.settings.evolution.generations);
  }
  std::string reason = "--force:";
  for (const std::string& p : plan.forced) reason += " " + p + ";";
  reason.pop_back();
  return reason;
}

}  // namespace animat
