// What starting a run, or continuing the store's run, will do: decided by
// reading the store only, so that a start-up that fails after planning (a
// port in use) leaves the store as it was; EvolutionRun::Begin then
// carries the plan out. Not thread-safe (the store is not).
#ifndef ANIMAT_MASTER_RUN_RUN_PLAN_H_
#define ANIMAT_MASTER_RUN_RUN_PLAN_H_

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/base/status.h"
#include "master/evolution/evolution_params.h"
#include "master/lineage/store.h"

namespace animat {

struct RunPlan {
  int64_t run_id = 0;    // The run to continue; 0 for a new run.
  RunSettings settings;  // What the run runs with.
  // Of the run to continue: its state ("running" or "finished") and the
  // generations it has made.
  std::string state;
  int generations_made = 0;
  // The run's recorded configuration and build are replaced by `settings`
  // and this build (an extended run, or --force).
  bool update_config = false;
  std::vector<std::string> forced;  // What --force overrides, for the log.
};

// Why a plan with update_config changes the run's recorded configuration,
// for its configuration history: "--force: WHAT IT OVERRIDES; ...", or
// "generations set to N" (a run extended).
std::string ConfigChangeReason(const RunPlan& plan);

// A new run in `store`, which must hold none (kInvalidArgument otherwise,
// saying so).
Result<RunPlan> PlanStart(lineage::Store* store, const RunSettings& settings);

// Continues the store's run (kNotFound when it holds none). Refuses,
// saying why, when `settings` is given and differs from the stored
// configuration, or when the store was written by another simulator
// build, unless `force`. `generations`, when set, replaces the run's number
// of generations (to extend a finished run).
Result<RunPlan> PlanResume(lineage::Store* store,
                           const std::optional<RunSettings>& settings,
                           bool force, std::optional<int> generations);

}  // namespace animat

#endif  // ANIMAT_MASTER_RUN_RUN_PLAN_H_
