// animat-worker --connect ENDPOINT [--threads N] [--heartbeat-ms MS]
//               [--exit-when-done] [--idle-timeout S] [--log-items]
//               [--curve-server MASTER.pub --curve-secret WORKER.key]
// animat-worker --evaluate-one REQUEST --result RESULT
//
// Evaluates animats for a master until SIGTERM or SIGINT; then hands back
// the work it has not started, finishes what it is evaluating, and exits 0.
// With --exit-when-done it also exits 0 when the master says its run is
// over, and with --idle-timeout when no master has welcomed it for S
// seconds. Exits 3 when the master refuses it (another protocol version or
// build), 2 on a usage error. --evaluate-one (first, when given) is what
// a master runs to evaluate one genome alone (worker/evaluate_one.h): exit
// 0 once RESULT is written, 2 when it cannot be.
#include <csignal>
#include <iostream>
#include <optional>
#include <string>
#include <thread>

#include <google/protobuf/stubs/logging.h>
#include <CLI/CLI.hpp>

#include "common/command_line/command_line.h"
#include "common/kernels/isa.h"
#include "common/protocol/endpoint.h"
#include "common/security/curve_keys.h"
#include "worker/evaluate_one.h"
#include "worker/worker.h"

namespace {

animat::Worker* g_worker = nullptr;

void OnSignal(int) {
  if (g_worker != nullptr) g_worker->Stop();
}

// The key files named on the command line.
struct KeyFiles {
  std::string server;  // The master's public key.
  std::string secret;  // This worker's key pair.
};

// Declares the options into `options` and `keys`.
void AddOptions(CLI::App& app, animat::WorkerOptions& options, KeyFiles& keys) {
  app.add_option("--connect", options.endpoint,
                 "The master's endpoint: tcp://HOST:PORT or ipc://PATH")
      ->required()
      ->check([](const std::string& endpoint) {
        return animat::protocol::CheckEndpoint(
                   endpoint, animat::protocol::EndpointUse::kConnect)
            .message();
      });
  app.add_option("--threads", options.threads,
                 "Evaluations at once (default: one per core)")
      ->check(CLI::Range(1, 4096));
  app.add_option("--heartbeat-ms", options.heartbeat_ms,
                 "Heartbeat interval until the master sets its own")
      ->check(CLI::Range(10, 600000))
      ->capture_default_str();
  app.add_flag("--exit-when-done", options.exit_when_done,
               "Exit when the master says its run is over");
  app.add_option("--idle-timeout", options.idle_timeout_s,
                 "Exit after this many seconds without a master (0: never)")
      ->check(CLI::Range(0, 100000000))
      ->capture_default_str();
  app.add_flag("--log-items", options.log_items,
               "Log the individuals of every work message received");
  auto* null_evaluation =
      app.add_flag("--null-evaluation", options.null_evaluation,
                   "Evaluate nothing; answer at once (dispatch benchmarks)");
  app.add_option("--null-delay-ms", options.null_delay.mean_ms,
                 "With --null-evaluation: take this long on average per "
                 "item, on the worker's threads (benchmarks)")
      ->check(CLI::Range(0.0, 60000.0))
      ->needs(null_evaluation);
  app.add_option("--null-delay-cv", options.null_delay.cv,
                 "With --null-delay-ms: the delays' coefficient of "
                 "variation (log-normal, a pure function of the genome)")
      ->check(CLI::Range(0.0, 10.0))
      ->needs(null_evaluation);
  auto* server =
      app.add_option("--curve-server", keys.server,
                     "CurveZMQ: the master's public key file (animat keygen)");
  auto* secret = app.add_option(
      "--curve-secret", keys.secret,
      "CurveZMQ: this worker's key pair file; its public key must be on "
      "the master's allow-list");
  server->needs(secret);
  secret->needs(server);
  app.set_version_flag("--version", animat::protocol::VersionText(),
                       "Print the build id, protocol and model versions");
}

// Reads the CurveZMQ keys, if named, into `options`.
animat::Status ReadKeys(const KeyFiles& keys, animat::WorkerOptions& options) {
  if (keys.server.empty()) return animat::Status::Ok();
  animat::Result<std::string> server_key =
      animat::security::ReadPublicKey(keys.server);
  if (!server_key.ok()) return server_key.status();
  animat::Result<animat::security::CurveKeyPair> pair =
      animat::security::ReadKeyPair(keys.secret);
  if (!pair.ok()) return pair.status();
  options.curve_server_key = *server_key;
  options.curve_public_key = pair->public_key;
  options.curve_secret_key = pair->secret_key;
  return animat::Status::Ok();
}

// animat-worker --evaluate-one REQUEST --result RESULT.
int EvaluateOneMain(int argc, char** argv) {
  std::string request, result;
  CLI::App app{
      "animat-worker --evaluate-one: evaluates one genome alone for a master"};
  app.add_option("--evaluate-one", request,
                 "The request (animat.v1.IsolatedEvaluation, binary)")
      ->required();
  app.add_option("--result", result, "Where the WorkResult goes (binary)")
      ->required();
  if (const std::optional<int> code =
          animat::ParseCommandLine(app, argc, argv, "animat-worker")) {
    return *code;
  }
  return animat::EvaluateOne(
      request, result, animat::Prefixed("animat-worker", animat::StderrSink));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && std::string(argv[1]) == "--evaluate-one") {
    return EvaluateOneMain(argc, argv);
  }
  animat::WorkerOptions options;
  options.threads = static_cast<int>(std::thread::hardware_concurrency());
  if (options.threads < 1) options.threads = 1;
  CLI::App app{"animat-worker: evaluates animats for an animat master"};
  KeyFiles keys;
  AddOptions(app, options, keys);
  if (const std::optional<int> code =
          animat::ParseCommandLine(app, argc, argv, "animat-worker")) {
    return *code;
  }
  // A mistyped ANIMAT_ISA is refused, not silently replaced.
  if (const animat::Result<animat::Isa> isa = animat::IsaFromEnvironment();
      !isa.ok()) {
    std::cerr << "animat-worker: " << isa.status().message() << "\n";
    return 2;
  }

  if (animat::Status status = ReadKeys(keys, options); !status.ok()) {
    std::cerr << "animat-worker: " << status.message() << "\n";
    return 2;
  }

  // Malformed input is reported through our log; protobuf's own lines
  // about it would only repeat it outside the log.
  google::protobuf::SetLogHandler(nullptr);
  animat::Worker worker(options);
  g_worker = &worker;
  struct sigaction action = {};
  action.sa_handler = OnSignal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGTERM, &action, nullptr);
  sigaction(SIGINT, &action, nullptr);
  const int code = worker.Run();
  g_worker = nullptr;
  return code;
}
