// The state of a campaign's runs, read from their stores (read only, with
// no lock: the campaign may be running), for `animat campaign status`.
// Thread-safe (no shared state).
#ifndef ANIMAT_MASTER_CAMPAIGN_CAMPAIGN_STATUS_H_
#define ANIMAT_MASTER_CAMPAIGN_CAMPAIGN_STATUS_H_

#include <optional>
#include <string>
#include <vector>

#include "common/base/status.h"

namespace animat {

struct RunStatus {
  std::string name;  // The store's file name without ".db".
  // "finished", "in progress" (not finished: running, or stopped until the
  // campaign is started again), "not started" (no store, or no run in it)
  // or "unreadable: WHY".
  std::string state;
  int generations_done = 0;  // Completed generations.
  // Of the run's configuration (its extend_to once the run has decided
  // to go on: EvolutionLength); 0 if unknown.
  int generations = 0;
  std::optional<double> best, mean;  // Of the last completed generation.
};

// The runs of the stores DIR/*.db, by name; with `names`, those runs in
// that order instead (a campaign file's), stores missing or not.
Result<std::vector<RunStatus>> ReadCampaignStatus(
    const std::string& dir,
    const std::optional<std::vector<std::string>>& names);

// The table `animat campaign status` prints: a header, a line per run,
// then "N of M runs finished".
std::string FormatCampaignStatus(const std::vector<RunStatus>& runs);

}  // namespace animat

#endif  // ANIMAT_MASTER_CAMPAIGN_CAMPAIGN_STATUS_H_
