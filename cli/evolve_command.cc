// animat evolve --config FILE --db FILE [--workers N] [--generations G]
//
// The embedded default: a master on loopback and N local worker processes
// in one command. Run it again with the same --db to continue; Ctrl-C
// leaves a resumable store.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <climits>
#include <cstdio>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>
#include <zmq.hpp>

#include "cli/commands.h"
#include "master/dispatch/dispatcher.h"
#include "master/progress.h"
#include "master/run/evolution_run.h"

extern char** environ;

namespace animat::cli {
namespace {

std::atomic<bool> g_stop{false};

void OnSignal(int) { g_stop.store(true); }

struct Options {
  std::string config;
  std::string db;
  int workers = 0;
  std::optional<int> generations;
  bool force = false;
};

// The animat-worker beside this program.
std::string WorkerPath() {
  char self[PATH_MAX];
  const ssize_t n = readlink("/proc/self/exe", self, sizeof(self) - 1);
  if (n <= 0) return "animat-worker";
  std::string path(self, static_cast<size_t>(n));
  return path.substr(0, path.rfind('/') + 1) + "animat-worker";
}

// Local worker processes; stopped (SIGTERM, then waited for) on
// destruction.
class LocalWorkers {
 public:
  Status Start(int count, const std::string& endpoint,
               const std::string& log_path) {
    const std::string binary = WorkerPath();
    for (int i = 0; i < count; ++i) {
      posix_spawn_file_actions_t actions;
      posix_spawn_file_actions_init(&actions);
      posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO,
                                       log_path.c_str(),
                                       O_WRONLY | O_CREAT | O_APPEND, 0644);
      posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
      std::vector<std::string> args = {binary, "--connect", endpoint,
                                       "--threads", "1"};
      std::vector<char*> argv;
      for (std::string& a : args) argv.push_back(a.data());
      argv.push_back(nullptr);
      pid_t pid;
      const int rc = posix_spawn(&pid, binary.c_str(), &actions, nullptr,
                                 argv.data(), environ);
      posix_spawn_file_actions_destroy(&actions);
      if (rc != 0) {
        return Status::IoError("cannot start " + binary + ": " +
                               std::strerror(rc));
      }
      pids_.push_back(pid);
    }
    return Status::Ok();
  }
  ~LocalWorkers() {
    for (pid_t pid : pids_) kill(pid, SIGTERM);
    for (pid_t pid : pids_) waitpid(pid, nullptr, 0);
  }

 private:
  std::vector<pid_t> pids_;
};

int Run(const Options& o) {
  // A mistyped path must not leave an empty store behind.
  if (o.config.empty() && access(o.db.c_str(), F_OK) != 0) {
    return Fail(o.db +
                ": no such lineage store; --config is needed to start a run");
  }
  std::optional<RunSettings> settings;
  if (!o.config.empty()) {
    Result<RunSettings> read = ReadRunConfigFile(o.config);
    if (!read.ok()) return Fail(read.status().message());
    settings = std::move(read).value();
    if (o.generations) settings->evolution.generations = *o.generations;
  }
  // From here on SIGTERM and SIGINT (Ctrl-C) stop the run cleanly (at the
  // latest after its first step), whenever they come.
  struct sigaction action = {};
  action.sa_handler = OnSignal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGTERM, &action, nullptr);
  sigaction(SIGINT, &action, nullptr);

  Result<std::unique_ptr<lineage::Store>> store = lineage::Store::Open(o.db);
  if (!store.ok()) return Fail(store.status().message());
  Result<std::vector<lineage::RunRow>> runs = (*store)->Runs();
  if (!runs.ok()) return Fail(runs.status().message());
  // --generations counts them all: fewer than the run has made runs
  // nothing (and must not rewrite the run's configuration).
  if (!runs->empty() && o.generations) {
    const lineage::RunRow& last = runs->back();
    Result<std::optional<lineage::GenerationRow>> latest =
        (*store)->LatestGenerationHead(last.run_id);
    if (!latest.ok()) return Fail(latest.status().message());
    const int made = *latest ? (*latest)->generation + 1 : 0;
    if (*o.generations < made) {
      return Fail(o.db + " holds run " + std::to_string(last.run_id) + " (" +
                  last.state + ") with " + std::to_string(made) +
                  " generations; --generations " +
                  std::to_string(*o.generations) +
                  " counts them all, so there is nothing to run. To extend "
                  "it, ask for more than " +
                  std::to_string(made) + ": animat evolve --db " + o.db +
                  " --generations " + std::to_string(made + 10));
    }
  }
  const LogSink log = Prefixed("evolve", StderrSink);
  Result<std::unique_ptr<EvolutionRun>> run =
      runs->empty()
          ? (settings ? EvolutionRun::Start(store->get(), *settings, log)
                      : Result<std::unique_ptr<EvolutionRun>>(
                            Status::InvalidArgument(
                                o.db + " holds no run: --config is needed")))
          : EvolutionRun::Resume(store->get(), settings, o.force, o.generations,
                                 log);
  if (!run.ok()) return Fail(run.status().message());

  zmq::context_t context(1);
  DispatcherOptions options;
  options.endpoint = "tcp://127.0.0.1:*";
  options.log = [](std::string_view) {};  // Joins and leaves are routine.
  // Workers keep each result until the run has committed it.
  options.acknowledge_on_receipt = false;
  Result<std::unique_ptr<Dispatcher>> dispatcher = Dispatcher::Create(
      &context, options, ConfigToProto((*run)->model_config()));
  if (!dispatcher.ok()) return Fail(dispatcher.status().message());
  const int count =
      o.workers > 0
          ? o.workers
          : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  LocalWorkers workers;
  const std::string worker_log = o.db + ".workers.log";
  Status status = workers.Start(count, (*dispatcher)->endpoint(), worker_log);
  if (!status.ok()) return Fail(status.message());
  log(std::to_string(count) + " local workers (their log: " + worker_log + ")");

  status = (*run)->Run(dispatcher->get(), g_stop,
                       [](const GenerationReport& report) {
                         std::printf("%s\n", FormatProgress(report).c_str());
                         std::fflush(stdout);
                       });
  if (!status.ok()) return Fail(status.message());
  if ((*run)->finished()) {
    log("finished; the best: animat lineage best --db " + o.db);
  } else {
    log("stopped; run the same command again to continue");
  }
  return 0;
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
  return [options] { return Run(*options); };
}

}  // namespace animat::cli
