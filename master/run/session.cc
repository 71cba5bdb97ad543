#include "master/run/session.h"

#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <memory>
#include <mutex>
#include <utility>
#include <zmq.hpp>

#include "common/evaluation/model_config.h"
#include "common/protocol/endpoint.h"
#include "common/security/curve_keys.h"
#include "master/dispatch/dispatcher.h"
#include "master/lineage/store.h"
#include "master/run/child_isolation.h"
#include "master/run/local_workers.h"

namespace animat {
namespace {

std::atomic<bool> g_stop{false};

void OnStopSignal(int) { g_stop.store(true); }

bool Exists(const std::string& path) { return access(path.c_str(), F_OK) == 0; }

// What can be said of the request without reading any file; a mistyped
// path must not leave an empty store behind.
Status CheckRequest(const SessionOptions& o) {
  // (An empty path would be a private in-memory store, lost at exit.)
  if (o.db_path.empty()) {
    return Status::InvalidArgument("--db needs the path of a lineage store");
  }
  switch (o.choice) {
    case RunChoice::kStart:
      if (o.config_path.empty()) {
        return Status::InvalidArgument(
            "--config is needed to start a run (or --resume)");
      }
      break;
    case RunChoice::kResume:
      if (!Exists(o.db_path)) {
        return Status::NotFound(o.db_path +
                                ": no such lineage store to resume");
      }
      break;
    case RunChoice::kStartOrResume:
      if (o.config_path.empty() && !Exists(o.db_path)) {
        return Status::NotFound(
            o.db_path +
            ": no such lineage store; --config is needed to start a run");
      }
      break;
  }
  return Status::Ok();
}

Result<std::optional<RunSettings>> ReadSettings(const SessionOptions& o) {
  if (o.config_path.empty()) return std::optional<RunSettings>();
  Result<RunSettings> read = ReadRunConfigFile(o.config_path);
  if (!read.ok()) return read.status();
  if (o.generations) read->evolution.generations = *o.generations;
  return std::optional<RunSettings>(std::move(read).value());
}

}  // namespace

const std::atomic<bool>& InstallStopHandlers() {
  struct sigaction action = {};
  action.sa_handler = OnStopSignal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGTERM, &action, nullptr);
  sigaction(SIGINT, &action, nullptr);
  return g_stop;
}

Result<DispatcherOptions> ListenOptions(const SessionOptions& o) {
  Status endpoint =
      protocol::CheckEndpoint(o.bind, protocol::EndpointUse::kBind);
  if (!endpoint.ok()) return endpoint.WithPrefix("--bind");
  DispatcherOptions options;
  options.endpoint = o.bind;
  options.heartbeat_ms = o.heartbeat_ms;
  options.insecure = o.insecure;
  options.log = o.dispatcher_log;
  options.notices = o.log;  // "No worker has joined", even from evolve.
  // Workers keep each result until the run has committed it.
  options.acknowledge_on_receipt = false;
  if (!o.curve_secret_file.empty()) {
    Result<security::CurveKeyPair> pair =
        security::ReadKeyPair(o.curve_secret_file);
    if (!pair.ok()) return pair.status();
    Result<std::map<std::string, std::string>> allowed =
        security::ReadAllowList(o.curve_allow_file);
    if (!allowed.ok()) return allowed.status();
    options.curve_secret_key = pair->secret_key;
    options.curve_allowed = std::move(allowed).value();
  }
  Status status = Dispatcher::CheckOptions(options);
  if (!status.ok()) return status;
  return options;
}

namespace {

// "To extend it, ...": the command that runs 10 generations more.
std::string ExtendHint(const SessionOptions& o, int made) {
  return o.resume_command + " --generations " + std::to_string(made + 10);
}

// Start or resume, as asked and as the store holds; reads the store only.
Result<RunPlan> Plan(lineage::Store* store, const SessionOptions& o,
                     const std::optional<RunSettings>& settings) {
  bool resume = o.choice == RunChoice::kResume;
  if (o.choice == RunChoice::kStartOrResume) {
    Result<std::vector<lineage::RunRow>> runs = store->Runs();
    if (!runs.ok()) return runs.status();
    resume = !runs->empty();
    if (!resume && !settings) {
      return Status::InvalidArgument(o.db_path +
                                     " holds no run: --config is needed");
    }
  }
  if (!resume) return PlanStart(store, *settings);
  Result<RunPlan> plan = PlanResume(store, settings, o.force, o.generations);
  if (!plan.ok()) return plan;
  // --generations counts them all: fewer than the run has made runs
  // nothing (and must not rewrite the run's configuration).
  const int made = plan->generations_made;
  if (o.generations && *o.generations < made) {
    return Status::InvalidArgument(
        o.db_path + " holds run " + std::to_string(plan->run_id) + " (" +
        plan->state + ") with " + std::to_string(made) +
        " generations; --generations " + std::to_string(*o.generations) +
        " counts them all, so there is nothing to run. To extend it, ask "
        "for more than " +
        std::to_string(made) + ": " + ExtendHint(o, made));
  }
  return plan;
}

// A finished run that the plan does not extend: nothing to serve.
bool NothingToRun(const RunPlan& plan) {
  return plan.run_id != 0 && plan.state == "finished" && !plan.update_config;
}

}  // namespace

Status StartLocalWorkers(const SessionOptions& o, const Dispatcher& dispatcher,
                         LocalWorkers* workers) {
  if (o.local_workers <= 0) return Status::Ok();
  LocalWorkerOptions worker;
  worker.binary = WorkerBesideThisProgram();
  worker.endpoint = dispatcher.endpoint();
  worker.threads = 1;
  worker.exit_when_done = true;
  // A master killed with SIGKILL cannot stop them: they go by themselves.
  worker.idle_timeout_s = kLocalWorkerIdleTimeoutS;
  worker.log_path = o.worker_log;
  Status status = workers->Start(o.local_workers, worker);
  if (!status.ok()) return status;
  o.log(std::to_string(o.local_workers) +
        " local workers (their log: " + o.worker_log + ")");
  return Status::Ok();
}

namespace {

// Serves the run until it ends or a signal stops it, then says what next.
Status Serve(EvolutionRun* run, Dispatcher* dispatcher, const SessionOptions& o,
             const std::atomic<bool>& stop) {
  LocalWorkers workers;
  Status status = StartLocalWorkers(o, *dispatcher, &workers);
  if (!status.ok()) return status;
  status = run->Run(dispatcher, stop, o.progress);
  if (!status.ok()) return status;
  if (run->finished()) {
    // Workers started for this run may go (--exit-when-done).
    dispatcher->Farewell("the run is finished");
    o.outcome("finished; the best: animat lineage best --db " +
              CommandLine({o.db_path}));
  } else {
    o.outcome("stopped; resume with: " + o.resume_command);
  }
  return Status::Ok();
}

}  // namespace

void StdoutSink(std::string_view line) {
  static std::mutex mutex;
  std::lock_guard<std::mutex> lock(mutex);
  std::fwrite(line.data(), 1, line.size(), stdout);
  std::fputc('\n', stdout);
  std::fflush(stdout);
}

std::string CommandLine(const std::vector<std::string>& words) {
  std::string line;
  for (const std::string& word : words) {
    if (!line.empty()) line += ' ';
    const bool plain =
        !word.empty() && word.find_first_not_of(
                             "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstu"
                             "vwxyz0123456789-_./:=@%+,") == std::string::npos;
    if (plain) {
      line += word;
      continue;
    }
    line += '\'';
    for (char c : word)
      line += c == '\'' ? std::string("'\\''") : std::string(1, c);
    line += '\'';
  }
  return line;
}

Status RunSession(const SessionOptions& o) {
  // The request, the configuration, the keys and the endpoint before the
  // store is touched.
  Status status = CheckRequest(o);
  if (!status.ok()) return status;
  Result<std::optional<RunSettings>> settings = ReadSettings(o);
  if (!settings.ok()) return settings.status();
  Result<DispatcherOptions> listen = ListenOptions(o);
  if (!listen.ok()) return listen.status();
  const std::atomic<bool>& stop = InstallStopHandlers();

  Result<std::unique_ptr<lineage::Store>> store =
      lineage::Store::Open(o.db_path, *listen->clock);
  if (!store.ok()) return store.status();
  Result<RunPlan> plan = Plan(store->get(), o, *settings);
  if (!plan.ok()) return plan.status();
  if (NothingToRun(*plan)) {
    o.outcome("run " + std::to_string(plan->run_id) + " is finished (" +
              std::to_string(plan->generations_made) +
              " generations); to extend it: " +
              ExtendHint(o, plan->generations_made));
    return Status::Ok();
  }
  // Bound before the run is written: a port in use leaves the store as it
  // was.
  zmq::context_t context(1);
  // Suspects are evaluated alone by the animat-worker beside this program;
  // it outlives the dispatcher.
  Result<std::unique_ptr<ChildIsolation>> isolation = ChildIsolation::Create(
      {{WorkerBesideThisProgram()}, listen->lease_ms, listen->clock});
  if (!isolation.ok()) return isolation.status();
  listen->isolation = isolation->get();
  Result<std::unique_ptr<Dispatcher>> dispatcher = Dispatcher::Create(
      &context, *listen, ConfigToProto(plan->settings.model));
  if (!dispatcher.ok()) return dispatcher.status();
  Result<std::unique_ptr<EvolutionRun>> run =
      EvolutionRun::Begin(store->get(), *plan, o.log);
  if (!run.ok()) return run.status();
  return Serve(run->get(), dispatcher->get(), o, stop);
}

}  // namespace animat
