// The start-up path of a campaign (docs/evolution.md, "Campaigns"),
// shared by `animat campaign` and `animat-master --campaign`: reads the
// campaign file, opens each run's store DIR/<name>.db and plans it (start,
// resume, or nothing for a finished run), binds one dispatcher, writes
// the runs, starts the local workers if asked, then serves every run at
// once from one pool of workers until all are finished or a signal stops
// them; the same command again resumes each run where it stopped.
//
// Each run is the EvolutionRun a lone run is, on a thread of its own,
// through its lane of a SharedEvaluators (shared_evaluators.h); this
// thread pumps the dispatcher. So each store holds what the same run made
// alone holds, whatever the other runs, the workers and the faults.
//
// Runs may differ in their model configuration (drag, contacts,
// signals ...): a worker is sent each one with the first work of it
// (docs/protocol.md), up to protocol::kMaxConfigs distinct ones at once.
//
// Runs on the calling thread (plus one thread per run, and their
// offspring threads); one session per process (the signal handlers).
#ifndef ANIMAT_MASTER_CAMPAIGN_CAMPAIGN_SESSION_H_
#define ANIMAT_MASTER_CAMPAIGN_CAMPAIGN_SESSION_H_

#include <functional>
#include <string>

#include "common/base/status.h"
#include "master/run/evolution_run.h"
#include "master/run/session.h"

namespace animat {

struct CampaignOptions {
  std::string campaign_path;  // The campaign file (.txtpb or .json).
  std::string dir;            // The stores' folder; made if missing.
  // Where and how workers connect, the local workers and their log, the
  // log sinks, the outcome line and the resume command, as for a lone run
  // (session.h). Its config_path, db_path, choice, force, generations and
  // progress are not used. The log sinks are called from several threads
  // (the runs').
  SessionOptions session;
  // After each generation of each run (from that run's thread): the run's
  // name and its report.
  std::function<void(const std::string& run, const GenerationReport&)> progress;
  // The campaign line (runs finished, evaluations per second, time left)
  // at least this often (seconds), and whenever a run finishes.
  double campaign_line_seconds = 30;
};

// Runs the campaign until every run is finished or SIGTERM/SIGINT (then
// every run commits what came in and stays resumable). A campaign whose
// runs are all finished says so and changes nothing; runs added to the
// file since start alone. Errors name the run and say what is wrong.
Status RunCampaign(const CampaignOptions& options);

}  // namespace animat

#endif  // ANIMAT_MASTER_CAMPAIGN_CAMPAIGN_SESSION_H_
