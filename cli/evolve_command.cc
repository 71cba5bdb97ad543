// animat evolve --config FILE --db FILE [--workers N] [--generations G]
//
// The embedded default: a master on loopback and N local worker processes
// in one command (master/run/session.h, as animat-master starts). Run it
// again with the same --db to continue; Ctrl-C leaves a resumable store.
#include <algorithm>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "cli/commands.h"
#include "master/progress.h"
#include "master/run/session.h"

namespace animat::cli {
namespace {

struct Options {
  std::string config;
  std::string db;
  int workers = 0;
  std::optional<int> generations;
  bool force = false;
};

// `program`: the animat tool as it was started, for the resume hint.
int Run(const Options& options, const std::string& program) {
  SessionOptions o;
  o.config_path = options.config;
  o.db_path = options.db;
  o.choice = RunChoice::kStartOrResume;
  o.force = options.force;
  o.generations = options.generations;
  o.bind = "tcp://127.0.0.1:*";
  o.local_workers =
      options.workers > 0
          ? options.workers
          : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  o.worker_log = options.db + ".workers.log";
  std::vector<std::string> resume = {program, "evolve", "--db", options.db};
  if (options.workers > 0) {
    resume.insert(resume.end(), {"--workers", std::to_string(options.workers)});
  }
  o.resume_command = CommandLine(resume);
  o.log = Prefixed("evolve", StderrSink);
  o.dispatcher_log = [](std::string_view) {};  // Joins and leaves are routine.
  // Progress is a log line on standard error, as animat-master's; standard
  // output carries only the session's closing line.
  o.progress = [log = o.log](const GenerationReport& report) {
    log(FormatProgress(report));
  };
  const Status status = RunSession(o);
  return status.ok() ? 0 : Fail(status.message());
}

}  // namespace

Command AddEvolveCommand(CLI::App& app) {
  auto options = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "evolve",
      "Run an evolution on this machine: a master and local workers; run "
      "again with the same --db to continue");
  sub->add_option("--config", options->config,
                  "Run configuration (animat.v1.RunConfig; needed to start)");
  sub->add_option("--db", options->db, "The lineage store (SQLite)")
      ->required();
  sub->add_option("--workers", options->workers,
                  "Local worker processes (default: one per core)")
      ->check(CLI::Range(1, 4096));
  sub->add_option("--generations", options->generations,
                  "Run this many generations in all")
      ->check(CLI::Range(1, 100000000));
  sub->add_flag("--force", options->force,
                "Continue even with another configuration or build");
  // After parsing, the app's name is argv[0] (CLI11 names an unnamed app
  // so).
  return [options, &app] {
    return Run(*options, app.get_name().empty() ? "animat" : app.get_name());
  };
}

}  // namespace animat::cli
