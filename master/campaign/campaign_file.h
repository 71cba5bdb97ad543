// A campaign file (proto/animat/v1/campaign.proto) expanded into its runs:
// each a name, which is also its store's (DIR/<name>.db), and the run
// settings that a run configuration file with the same fields would give,
// so that a campaign's run and the same run made alone with `animat
// evolve` record the same configuration (docs/evolution.md, "Campaigns").
//
// Thread-safe (no shared state).
#ifndef ANIMAT_MASTER_CAMPAIGN_CAMPAIGN_FILE_H_
#define ANIMAT_MASTER_CAMPAIGN_CAMPAIGN_FILE_H_

#include <string>
#include <vector>

#include "animat/v1/campaign.pb.h"
#include "common/base/status.h"
#include "master/evolution/evolution_params.h"

namespace animat {

struct CampaignRun {
  std::string name;      // Unique in the campaign; a file name without ".db".
  v1::RunConfig config;  // As merged: the file, `set`, the axes, the seed.
  RunSettings settings;  // The same, checked and over the defaults.
};

// The runs of `campaign`, in the order written: for each CampaignRuns,
// each combination of axis values (the first axis varying slowest), each
// seed. Relative config paths are read from `base_dir`. Errors name the
// entry ("runs[1].axes[0].values[2].set: ...") and what is wrong: a file
// that cannot be read, fields that do not parse or are out of range, a
// label or name with characters a file name should not have, two runs of
// one name, no runs at all.
Result<std::vector<CampaignRun>> ExpandCampaign(const v1::Campaign& campaign,
                                                const std::string& base_dir);

// Reads the campaign file at `path` (.txtpb or .json) and expands it, its
// relative paths read from the file's folder. Errors start with the path.
Result<std::vector<CampaignRun>> ReadCampaignFile(const std::string& path);

}  // namespace animat

#endif  // ANIMAT_MASTER_CAMPAIGN_CAMPAIGN_FILE_H_
