// A real animat-worker process for the dispatch tests (a ChildProcess of
// tests/child_process.h): a worker exits only when told to, so one that
// exited by itself without a test waiting for it fails the test.
// Not thread-safe: one test thread uses it.
#ifndef ANIMAT_TESTS_DISPATCH_WORKER_PROCESS_H_
#define ANIMAT_TESTS_DISPATCH_WORKER_PROCESS_H_

#include <unistd.h>

#include <string>
#include <vector>

#include "tests/child_process.h"

namespace animat::testing {

struct WorkerArgs {
  std::string endpoint;  // The master's.
  int threads = 1;
  int heartbeat_ms = 100;  // Until the master's welcome sets its own.
  bool null_evaluation = false;
};

class WorkerProcess : public ChildProcess {
 public:
  // Starts ANIMAT_BIN_DIR/animat-worker; started() says whether it worked.
  explicit WorkerProcess(const WorkerArgs& args)
      : ChildProcess("animat-worker", Argv(args), Lifetime::kStaysUp) {}

  // "host:pid", as the dispatcher names the worker.
  std::string name() const {
    char host[256] = {};
    gethostname(host, sizeof(host) - 1);
    return std::string(host) + ":" + std::to_string(pid());
  }

 private:
  static std::vector<std::string> Argv(const WorkerArgs& args) {
    std::vector<std::string> argv = {
        std::string(ANIMAT_BIN_DIR) + "/animat-worker",
        "--connect",
        args.endpoint,
        "--threads",
        std::to_string(args.threads),
        "--heartbeat-ms",
        std::to_string(args.heartbeat_ms)};
    if (args.null_evaluation) argv.push_back("--null-evaluation");
    return argv;
  }
};

}  // namespace animat::testing

#endif  // ANIMAT_TESTS_DISPATCH_WORKER_PROCESS_H_
