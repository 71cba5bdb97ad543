// Local processes: the animat-worker processes `animat evolve` starts beside
// its master, and, through the same spawner, the programs the benchmarks
// and the end-to-end tests run (animat-master, animat, animat-worker).
//
// LocalProcess is one child (posix_spawn), with its output sent where the
// options say; LocalWorkers is a set of animat-worker processes connecting
// to one endpoint, stopped with SIGTERM (then SIGKILL after a grace
// period). Neither throws; failures to start come back as Status values.
// Not thread-safe: one thread uses each object.
#ifndef ANIMAT_MASTER_RUN_LOCAL_WORKERS_H_
#define ANIMAT_MASTER_RUN_LOCAL_WORKERS_H_

#include <sys/types.h>

#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/base/status.h"

namespace animat {

struct ProcessOptions {
  std::vector<std::string> argv;  // argv[0] is the program's path.
  // Files standard output and standard error go to ("": the parent's).
  // When both name the same file it is opened once, so the two streams
  // interleave in the order written.
  std::string stdout_path;
  std::string stderr_path;
  bool truncate = false;  // Truncate the files instead of appending.
  // The child leads a process group of its own, so SignalGroup reaches
  // whatever it starts in turn (and a terminal's Ctrl-C does not).
  bool own_process_group = false;
};

class LocalProcess {
 public:
  // Starts the program; kIoError, naming it, when it cannot be started.
  static Result<std::unique_ptr<LocalProcess>> Start(
      const ProcessOptions& options);
  // A child still running is killed (SIGKILL, to its group if it leads
  // one) and reaped: no process outlives its object.
  ~LocalProcess();
  LocalProcess(const LocalProcess&) = delete;
  LocalProcess& operator=(const LocalProcess&) = delete;

  pid_t pid() const { return pid_; }
  // Sends `signal` to the process, or to its whole group; false once it
  // has been reaped.
  bool Signal(int signal);
  bool SignalGroup(int signal);
  // Reaps the process if it has exited; true once it has (never blocks).
  bool Exited();
  // Blocks until the process exits, and reaps it.
  void Wait();
  // After an exit: its exit code, or -1 if a signal ended it; the signal
  // that ended it, or 0; either in words ("exit code 3", "signal Killed").
  int exit_code() const;
  int term_signal() const;
  std::string Describe() const;

 private:
  LocalProcess(pid_t pid, bool group) : pid_(pid), group_(group) {}
  bool Reap(int flags);

  pid_t pid_;
  bool group_;
  bool reaped_ = false;
  int status_ = 0;  // waitpid's, once reaped.
};

struct LocalWorkerOptions {
  std::string binary;    // The animat-worker to run.
  std::string endpoint;  // The master's.
  int threads = 1;
  int heartbeat_ms = 0;  // Until the master's welcome; 0: the default.
  bool null_evaluation = false;
  // With null_evaluation: each item's mean delay (ms; 0: none) and its
  // coefficient of variation (animat-worker --null-delay-ms, -cv).
  double null_delay_ms = 0;
  double null_delay_cv = 0;
  bool exit_when_done = false;  // Exit when the master's run is over.
  // Exit after this many seconds without a master (0: never), so that
  // workers outlive a master killed with SIGKILL only so long.
  int idle_timeout_s = 0;
  bool log_items = false;  // Log every work message received.
  // Where each worker's standard output and error are appended ("": the
  // parent's).
  std::string log_path;
};

// The animat-worker in the directory of the running program (e.g.
// build/bin/ beside animat).
std::string WorkerBesideThisProgram();
// The command line of a worker with these options.
std::vector<std::string> WorkerArgv(const LocalWorkerOptions& options);

class LocalWorkers {
 public:
  LocalWorkers() = default;
  ~LocalWorkers() { Stop(std::chrono::seconds(5)); }
  LocalWorkers(const LocalWorkers&) = delete;
  LocalWorkers& operator=(const LocalWorkers&) = delete;

  // Starts `count` more workers; kIoError when one cannot be started (those
  // started so far keep running).
  Status Start(int count, const LocalWorkerOptions& options);
  // Workers started and not stopped.
  size_t size() const { return workers_.size(); }
  // The first worker that has exited by itself ("exit code 3" for one that
  // was refused), or "" while all run. An exited worker is dropped.
  std::string Exited();
  // SIGTERM to every worker, then waits up to `grace` for them to exit,
  // calling `between` about every 5 ms meanwhile (e.g. to serve the
  // dispatcher, so that their goodbyes are heard) or sleeping; SIGKILL to
  // those still running.
  void Stop(std::chrono::milliseconds grace,
            const std::function<void()>& between = {});

 private:
  std::vector<std::unique_ptr<LocalProcess>> workers_;
};

}  // namespace animat

#endif  // ANIMAT_MASTER_RUN_LOCAL_WORKERS_H_
