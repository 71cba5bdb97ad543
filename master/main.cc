// animat-master: runs an evolution, serving workers over ZeroMQ and
// recording every individual in a SQLite lineage store.
//
//   animat-master --config FILE --db FILE [--bind ENDPOINT]
//   animat-master --resume --db FILE [--config FILE] [--force]
//                 [--generations G] [--bind ENDPOINT]
//   ... --bind tcp://0.0.0.0:5555 --curve-secret MASTER.key
//       --curve-allow WORKERS.allow        (or --insecure; docs/security.md)
//
// SIGTERM or SIGINT: commits what came in, leaves a resumable store and
// exits 0. Exit 1 on an error (the message says what), 2 on a usage error.
#include <atomic>
#include <csignal>
#include <iostream>
#include <optional>

#include <unistd.h>

#include <google/protobuf/stubs/logging.h>
#include <CLI/CLI.hpp>
#include <zmq.hpp>

#include "common/security/curve_keys.h"
#include "master/dispatch/dispatcher.h"
#include "master/progress.h"
#include "master/run/evolution_run.h"

namespace {

std::atomic<bool> g_stop{false};

void OnSignal(int) { g_stop.store(true); }

int Fail(const std::string& message) {
  std::cerr << "animat-master: " << message << "\n";
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  std::string config_path, db_path, bind = "tcp://127.0.0.1:5555";
  bool resume = false, force = false;
  std::optional<int> generations;
  int heartbeat_ms = animat::protocol::kHeartbeatMs;
  CLI::App app{"animat-master: evolves animats with workers over ZeroMQ"};
  app.add_option("--config", config_path,
                 "Run configuration (animat.v1.RunConfig, .json or .txtpb)");
  app.add_option("--db", db_path, "The lineage store (SQLite)")->required();
  app.add_option("--bind", bind, "Where workers connect")
      ->capture_default_str();
  app.add_flag("--resume", resume, "Continue the run in --db");
  app.add_flag("--force", force,
               "Resume even with another configuration or build");
  app.add_option("--generations", generations,
                 "Run this many generations in all (extends a finished run)")
      ->check(CLI::Range(1, 100000000));
  std::string curve_secret_file, curve_allow_file;
  bool insecure = false;
  auto* secret = app.add_option(
      "--curve-secret", curve_secret_file,
      "CurveZMQ: the master's key pair file (animat keygen); needed to "
      "listen beyond loopback");
  auto* allow =
      app.add_option("--curve-allow", curve_allow_file,
                     "CurveZMQ: the worker public keys to serve, one per line");
  auto* insecure_flag = app.add_flag(
      "--insecure", insecure,
      "Listen beyond loopback without CurveZMQ (trusted networks only)");
  secret->needs(allow);
  allow->needs(secret);
  insecure_flag->excludes(secret);
  app.add_option("--heartbeat-ms", heartbeat_ms, "Heartbeat interval")
      ->check(CLI::Range(10, 600000))
      ->capture_default_str();
  app.set_version_flag("--version", animat::protocol::VersionText(),
                       "Print the build id, protocol and model versions");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  if (!resume && config_path.empty()) {
    return Fail("--config is needed to start a run (or --resume)");
  }
  // A mistyped path must not leave an empty store behind.
  if (resume && access(db_path.c_str(), F_OK) != 0) {
    return Fail(db_path + ": no such lineage store to resume");
  }
  google::protobuf::SetLogHandler(nullptr);

  // Keys before the store: a master that cannot listen changes nothing.
  animat::DispatcherOptions options;
  options.endpoint = bind;
  options.heartbeat_ms = heartbeat_ms;
  options.insecure = insecure;
  // Workers keep each result until the run has committed it.
  options.acknowledge_on_receipt = false;
  if (!curve_secret_file.empty()) {
    animat::Result<animat::security::CurveKeyPair> pair =
        animat::security::ReadKeyPair(curve_secret_file);
    if (!pair.ok()) return Fail(pair.status().message());
    auto allowed = animat::security::ReadAllowList(curve_allow_file);
    if (!allowed.ok()) return Fail(allowed.status().message());
    options.curve_secret_key = pair->secret_key;
    options.curve_allowed = std::move(allowed).value();
  } else if (!insecure && !animat::security::IsLocalEndpoint(bind)) {
    return Fail("listening on " + bind +
                " reaches beyond this machine: give the master CurveZMQ keys "
                "(--curve-secret and --curve-allow, made by animat keygen; "
                "docs/security.md) or, on a trusted network only, "
                "--insecure");
  }

  std::optional<animat::RunSettings> settings;
  if (!config_path.empty()) {
    animat::Result<animat::RunSettings> read =
        animat::ReadRunConfigFile(config_path);
    if (!read.ok()) return Fail(read.status().message());
    settings = std::move(read).value();
    if (generations) settings->evolution.generations = *generations;
  }
  // From here on SIGTERM and SIGINT stop the run cleanly (at the latest
  // after its first step), whenever they come.
  struct sigaction action = {};
  action.sa_handler = OnSignal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGTERM, &action, nullptr);
  sigaction(SIGINT, &action, nullptr);

  animat::Result<std::unique_ptr<animat::lineage::Store>> store =
      animat::lineage::Store::Open(db_path);
  if (!store.ok()) return Fail(store.status().message());
  animat::Result<std::unique_ptr<animat::EvolutionRun>> run =
      resume ? animat::EvolutionRun::Resume(store->get(), settings, force,
                                            generations)
             : animat::EvolutionRun::Start(store->get(), *settings);
  if (!run.ok()) return Fail(run.status().message());

  zmq::context_t context(1);
  auto dispatcher = animat::Dispatcher::Create(
      &context, options, animat::ConfigToProto((*run)->model_config()));
  if (!dispatcher.ok()) return Fail(dispatcher.status().message());
  const animat::LogSink log = animat::Prefixed("master", animat::StderrSink);
  animat::Status status = (*run)->Run(
      dispatcher->get(), g_stop, [&](const animat::GenerationReport& report) {
        log(animat::FormatProgress(report));
      });
  if (!status.ok()) return Fail(status.message());
  if (!(*run)->finished()) {
    log("stopped; resume with: animat-master --resume --db " + db_path);
  }
  return 0;
}
