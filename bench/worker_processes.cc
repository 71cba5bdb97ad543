#include "bench/worker_processes.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>

#include "bench/timing.h"

namespace animat::bench {

Status CheckWorkerFiles(const std::string& binary, const std::string& log) {
  struct stat info;
  if (stat(binary.c_str(), &info) != 0) {
    return Status::InvalidArgument("--worker " + binary + ": " +
                                   std::strerror(errno));
  }
  if (!S_ISREG(info.st_mode)) {
    return Status::InvalidArgument("--worker " + binary +
                                   ": not a file (expected the animat-worker "
                                   "binary)");
  }
  if (access(binary.c_str(), X_OK) != 0) {
    return Status::InvalidArgument("--worker " + binary +
                                   ": not executable: " + std::strerror(errno));
  }
  // The workers append to it (master/run/local_workers.h).
  const int fd =
      open(log.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) {
    return Status::InvalidArgument(
        "--worker-log " + log +
        ": cannot append to it: " + std::strerror(errno));
  }
  close(fd);
  return Status::Ok();
}

WorkerProcesses::WorkerProcesses(std::string binary, std::string log,
                                 Dispatcher* dispatcher)
    : binary_(std::move(binary)),
      log_(std::move(log)),
      dispatcher_(dispatcher) {}

bool WorkerProcesses::Spawn(int count, int threads, bool null_evaluation,
                            double null_delay_ms, double null_delay_cv) {
  LocalWorkerOptions options;
  options.binary = binary_;
  options.endpoint = dispatcher_->endpoint();
  options.threads = threads;
  options.null_evaluation = null_evaluation;
  options.null_delay_ms = null_delay_ms;
  options.null_delay_cv = null_delay_cv;
  options.log_path = log_;
  const Status status = workers_.Start(count, options);
  if (!status.ok()) {
    std::fprintf(stderr, "%s\n", status.message().c_str());
    return false;
  }
  // Serve until every worker has said hello.
  const Clock::time_point start = Clock::now();
  while (dispatcher_->workers() < workers_.size()) {
    dispatcher_->Poll(10);
    const std::string exited = workers_.Exited();
    if (!exited.empty()) {
      std::fprintf(stderr,
                   "a worker exited (%s; exit code 3: refused) before "
                   "joining; see its log (%s)\n",
                   exited.c_str(), log_.c_str());
      return false;
    }
    if (SecondsSince(start) > 10) {
      std::fprintf(stderr, "workers did not join within 10 s\n");
      return false;
    }
  }
  return true;
}

void WorkerProcesses::Stop() {
  workers_.Stop(std::chrono::seconds(5), [this] { dispatcher_->Poll(5); });
}

}  // namespace animat::bench
