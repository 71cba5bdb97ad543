// animat campaign --campaign FILE --dir DIR [--workers N]
// animat campaign status --dir DIR [--campaign FILE]
//
// Many runs on this machine from one campaign file: one master and one
// pool of local workers serve them all (master/campaign/campaign_session.h);
// each run keeps its store DIR/<name>.db. Run it again to continue; Ctrl-C
// leaves every store resumable. `status` reads the stores, from another
// terminal too.
#include <algorithm>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "cli/commands.h"
#include "master/campaign/campaign_file.h"
#include "master/campaign/campaign_session.h"
#include "master/campaign/campaign_status.h"
#include "master/progress.h"

namespace animat::cli {
namespace {

struct Options {
  std::string campaign;
  std::string dir;
  int workers = 0;
};

int Run(const Options& options, const std::string& program) {
  CampaignOptions o;
  o.campaign_path = options.campaign;
  o.dir = options.dir;
  SessionOptions& s = o.session;
  s.bind = "tcp://127.0.0.1:*";
  s.local_workers =
      options.workers > 0
          ? options.workers
          : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  s.worker_log = options.dir + "/workers.log";
  std::vector<std::string> resume = {program,          "campaign", "--campaign",
                                     options.campaign, "--dir",    options.dir};
  if (options.workers > 0) {
    resume.insert(resume.end(), {"--workers", std::to_string(options.workers)});
  }
  s.resume_command = CommandLine(resume);
  s.log = Prefixed("campaign", StderrSink);
  s.dispatcher_log = [](std::string_view) {};  // Joins and leaves: routine.
  o.progress = [log = s.log](const std::string& run,
                             const GenerationReport& report) {
    log(run + ": " + FormatProgress(report));
  };
  const Status status = RunCampaign(o);
  return status.ok() ? 0 : Fail(status.message());
}

int ShowStatus(const Options& options) {
  std::optional<std::vector<std::string>> names;
  if (!options.campaign.empty()) {
    Result<std::vector<CampaignRun>> runs = ReadCampaignFile(options.campaign);
    if (!runs.ok()) return Fail(runs.status().message());
    names.emplace();
    for (const CampaignRun& run : *runs) names->push_back(run.name);
  }
  Result<std::vector<RunStatus>> status =
      ReadCampaignStatus(options.dir, names);
  if (!status.ok()) return Fail(status.status().message());
  std::cout << FormatCampaignStatus(*status);
  return 0;
}

}  // namespace

Command AddCampaignCommand(CLI::App& app) {
  auto options = std::make_shared<Options>();
  auto status_options = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "campaign",
      "Run many evolutions from a campaign file on this machine: one master "
      "and one pool of local workers for all; run again to continue");
  sub->require_subcommand(0, 1);
  sub->add_option("--campaign", options->campaign,
                  "The campaign file (animat.v1.Campaign; docs/evolution.md)");
  sub->add_option("--dir", options->dir,
                  "The folder of the runs' stores (DIR/<run>.db)");
  sub->add_option("--workers", options->workers,
                  "Local worker processes (default: one per core)")
      ->check(CLI::Range(1, 4096));
  CLI::App* status = sub->add_subcommand(
      "status", "A table of the campaign's runs, read from their stores");
  status
      ->add_option("--dir", status_options->dir,
                   "The folder of the runs' stores")
      ->required();
  status->add_option("--campaign", status_options->campaign,
                     "List the runs of this campaign file, in its order, "
                     "started or not");
  return [options, status_options, status, &app] {
    if (status->parsed()) return ShowStatus(*status_options);
    if (options->campaign.empty() || options->dir.empty()) {
      return Fail(
          "campaign: --campaign and --dir are needed (or: animat "
          "campaign status --dir DIR)");
    }
    return Run(*options, app.get_name().empty() ? "animat" : app.get_name());
  };
}

}  // namespace animat::cli
