// animat-worker --connect ENDPOINT [--threads N] [--heartbeat-ms MS]
//
// Evaluates animats for a master until SIGTERM or SIGINT; then hands back
// the work it has not started, finishes what it is evaluating, and exits 0.
// Exits 3 when the master refuses it (another protocol version or build),
// 2 on a usage error.
#include <csignal>
#include <thread>

#include <google/protobuf/stubs/logging.h>
#include <CLI/CLI.hpp>

#include "worker/worker.h"

namespace {

animat::Worker* g_worker = nullptr;

void OnSignal(int) {
  if (g_worker != nullptr) g_worker->Stop();
}

}  // namespace

int main(int argc, char** argv) {
  animat::WorkerOptions options;
  options.threads = static_cast<int>(std::thread::hardware_concurrency());
  if (options.threads < 1) options.threads = 1;
  CLI::App app{"animat-worker: evaluates animats for an animat master"};
  app.add_option("--connect", options.endpoint,
                 "The master's endpoint, e.g. tcp://127.0.0.1:5555")
      ->required();
  app.add_option("--threads", options.threads,
                 "Evaluations at once (default: one per core)")
      ->check(CLI::Range(1, 4096));
  app.add_option("--heartbeat-ms", options.heartbeat_ms,
                 "Heartbeat interval until the master sets its own")
      ->check(CLI::Range(10, 600000))
      ->capture_default_str();
  app.add_flag("--null-evaluation", options.null_evaluation,
               "Evaluate nothing; answer at once (dispatch benchmarks)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
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
