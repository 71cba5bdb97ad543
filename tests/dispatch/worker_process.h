// A real animat-worker process for the dispatch tests (a ChildProcess of
// tests/child_process.h): a worker exits only when told to, so one that
// exited by itself without a test waiting for it fails the test.
// Not thread-safe: one test thread uses it.
#ifndef ANIMAT_TESTS_DISPATCH_WORKER_PROCESS_H_
#define ANIMAT_TESTS_DISPATCH_WORKER_PROCESS_H_

#include <unistd.h>

#include <string>

#include "master/run/local_workers.h"
#include "tests/child_process.h"

namespace animat::testing {

// A test worker's options (master/run/local_workers.h): the animat-worker
// of ANIMAT_BIN_DIR, with a 100 ms heartbeat until the master's welcome
// sets its own.
struct WorkerArgs : LocalWorkerOptions {
  WorkerArgs() {
    binary = std::string(ANIMAT_BIN_DIR) + "/animat-worker";
    heartbeat_ms = 100;
  }
};

class WorkerProcess : public ChildProcess {
 public:
  // Starts ANIMAT_BIN_DIR/animat-worker; started() says whether it worked.
  explicit WorkerProcess(const WorkerArgs& args)
      : ChildProcess("animat-worker", WorkerArgv(args), Lifetime::kStaysUp) {}

  // "host:pid", as the dispatcher names the worker.
  std::string name() const {
    char host[256] = {};
    gethostname(host, sizeof(host) - 1);
    return std::string(host) + ":" + std::to_string(pid());
  }
};

}  // namespace animat::testing

#endif  // ANIMAT_TESTS_DISPATCH_WORKER_PROCESS_H_
