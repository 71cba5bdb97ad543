// animat-master: runs an evolution, serving workers over ZeroMQ and
// recording every individual in a SQLite lineage store.
//
//   animat-master --config FILE --db FILE [--bind ENDPOINT]
//   animat-master --resume --db FILE [--config FILE] [--force]
//                 [--generations G] [--bind ENDPOINT]
//   animat-master --campaign FILE --dir DIR [--bind ENDPOINT]
//                 (every run of a campaign; the same again resumes them)
//   ... --bind tcp://0.0.0.0:5555 --curve-secret MASTER.key
//       --curve-allow WORKERS.allow        (or --insecure; docs/security.md)
//
// SIGTERM or SIGINT: commits what came in, leaves a resumable store and
// exits 0. Exit 1 on an error (the message says what), 2 on a usage error.
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include <google/protobuf/stubs/logging.h>
#include <CLI/CLI.hpp>

#include "common/command_line/command_line.h"
#include "common/protocol/endpoint.h"
#include "master/campaign/campaign_session.h"
#include "master/progress.h"
#include "master/run/session.h"

namespace {

// Declares the options into `o` and `campaign` (campaign_path, dir).
void AddOptions(CLI::App& app, animat::SessionOptions& o, bool& resume,
                animat::CampaignOptions& campaign) {
  auto* config = app.add_option(
      "--config", o.config_path,
      "Run configuration (animat.v1.RunConfig, .json or .txtpb)");
  auto* db = app.add_option("--db", o.db_path, "The lineage store (SQLite)");
  auto* campaign_file = app.add_option(
      "--campaign", campaign.campaign_path,
      "Serve every run of this campaign file (docs/evolution.md) instead of "
      "one run; with --dir");
  auto* dir = app.add_option("--dir", campaign.dir,
                             "With --campaign: the folder of the runs' stores");
  campaign_file->needs(dir);
  dir->needs(campaign_file);
  campaign_file->excludes(db);
  campaign_file->excludes(config);
  app.add_option("--bind", o.bind,
                 "Where workers connect: tcp://HOST:PORT or ipc://PATH")
      ->capture_default_str()
      ->check([](const std::string& endpoint) {
        return animat::protocol::CheckEndpoint(
                   endpoint, animat::protocol::EndpointUse::kBind)
            .message();
      });
  app.add_flag("--resume", resume, "Continue the run in --db")
      ->excludes(campaign_file);
  app.add_flag("--force", o.force,
               "Resume even with another configuration or build")
      ->excludes(campaign_file);
  app.add_option("--generations", o.generations,
                 "Run this many generations in all (extends a finished run; "
                 "fewer than the run has made is refused)")
      ->check(CLI::Range(1, 100000000))
      ->excludes(campaign_file);
  auto* secret = app.add_option(
      "--curve-secret", o.curve_secret_file,
      "CurveZMQ: the master's key pair file (animat keygen); needed to "
      "listen beyond loopback");
  auto* allow =
      app.add_option("--curve-allow", o.curve_allow_file,
                     "CurveZMQ: the worker public keys to serve, one per line");
  auto* insecure = app.add_flag(
      "--insecure", o.insecure,
      "Listen beyond loopback without CurveZMQ (trusted networks only)");
  secret->needs(allow);
  allow->needs(secret);
  insecure->excludes(secret);
  app.add_option("--heartbeat-ms", o.heartbeat_ms, "Heartbeat interval")
      ->check(CLI::Range(10, 600000))
      ->capture_default_str();
  app.set_version_flag("--version", animat::protocol::VersionText(),
                       "Print the build id, protocol and model versions");
}

// Appends the options that make a master listen as `o` does: keys,
// --insecure, a heartbeat other than the default.
void AddListenWords(const animat::SessionOptions& o,
                    std::vector<std::string>* words) {
  if (!o.curve_secret_file.empty()) {
    words->insert(words->end(), {"--curve-secret", o.curve_secret_file,
                                 "--curve-allow", o.curve_allow_file});
  }
  if (o.insecure) words->push_back("--insecure");
  if (o.heartbeat_ms != animat::protocol::kHeartbeatMs) {
    words->insert(words->end(),
                  {"--heartbeat-ms", std::to_string(o.heartbeat_ms)});
  }
}

// The command that continues the run with the same endpoint and keys,
// starting `program` as this one was started (so that it runs as printed
// from the same directory).
std::string ResumeCommand(const std::string& program,
                          const animat::SessionOptions& o) {
  std::vector<std::string> words = {program,   "--resume", "--db",
                                    o.db_path, "--bind",   o.bind};
  AddListenWords(o, &words);
  return animat::CommandLine(words);
}

}  // namespace

// The command that continues every run of the campaign.
std::string CampaignCommand(const std::string& program,
                            const animat::CampaignOptions& c,
                            const animat::SessionOptions& o) {
  std::vector<std::string> words = {
      program, "--campaign", c.campaign_path, "--dir", c.dir, "--bind", o.bind};
  AddListenWords(o, &words);
  return animat::CommandLine(words);
}

// Every run of the campaign, served at once.
int RunCampaign(animat::CampaignOptions& c, const animat::SessionOptions& o,
                const std::string& program) {
  c.session = o;
  c.session.resume_command = CampaignCommand(program, c, o);
  const animat::LogSink log = o.log;
  c.progress = [log](const std::string& run,
                     const animat::GenerationReport& report) {
    log(run + ": " + animat::FormatProgress(report));
  };
  const animat::Status status = animat::RunCampaign(c);
  if (!status.ok()) {
    std::cerr << "animat-master: " << status.message() << "\n";
    return 1;
  }
  return 0;
}

int main(int argc, char** argv) {
  animat::SessionOptions o;
  animat::CampaignOptions campaign;
  bool resume = false;
  CLI::App app{"animat-master: evolves animats with workers over ZeroMQ"};
  AddOptions(app, o, resume, campaign);
  if (const std::optional<int> code =
          animat::ParseCommandLine(app, argc, argv, "animat-master")) {
    return *code;
  }
  google::protobuf::SetLogHandler(nullptr);
  const std::string program =
      argc > 0 && argv[0][0] != '\0' ? argv[0] : "animat-master";
  if (!campaign.campaign_path.empty()) {
    return RunCampaign(campaign, o, program);
  }
  if (o.db_path.empty()) {
    std::cerr << "animat-master: --db (one run) or --campaign with --dir (a "
                 "campaign) is needed\n";
    return 2;
  }
  o.choice = resume ? animat::RunChoice::kResume : animat::RunChoice::kStart;
  o.resume_command = ResumeCommand(program, o);
  // Progress is a log line (standard error); the closing line, standard
  // output.
  const animat::LogSink log = o.log;
  o.progress = [log](const animat::GenerationReport& report) {
    log(animat::FormatProgress(report));
  };
  const animat::Status status = animat::RunSession(o);
  if (!status.ok()) {
    std::cerr << "animat-master: " << status.message() << "\n";
    return 1;
  }
  return 0;
}
