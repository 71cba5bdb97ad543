// Real animat-worker processes for the benchmarks (master/run/local_workers.h)
// beside an in-process Dispatcher, which is served while they join and
// while they say goodbye; stopped with SIGTERM (then SIGKILL after 5 s)
// when Stop is called or the object is destroyed.
//
// Not thread-safe: the thread that serves the dispatcher uses it. The
// dispatcher must outlive the object.
#ifndef ANIMAT_BENCH_WORKER_PROCESSES_H_
#define ANIMAT_BENCH_WORKER_PROCESSES_H_

#include <string>

#include "common/base/status.h"
#include "master/dispatch/dispatcher.h"
#include "master/run/local_workers.h"

namespace animat::bench {

// What a benchmark checks before it starts: that `binary` (its --worker)
// is a file it may execute and that `log` (its --worker-log) can be opened
// for appending, which creates it if it does not exist. kInvalidArgument
// naming the flag and the path, and saying what is wrong, otherwise.
Status CheckWorkerFiles(const std::string& binary, const std::string& log);

class WorkerProcesses {
 public:
  // `binary`: the animat-worker to run; its output is appended to `log` (a
  // path; "/dev/null" discards it).
  WorkerProcesses(std::string binary, std::string log, Dispatcher* dispatcher);
  ~WorkerProcesses() { Stop(); }
  WorkerProcesses(const WorkerProcesses&) = delete;
  WorkerProcesses& operator=(const WorkerProcesses&) = delete;

  // Starts `count` workers of `threads` threads connecting to the
  // dispatcher's endpoint and serves the dispatcher until all have said
  // hello. Null-evaluation workers take `null_delay_ms` per item on average
  // with that coefficient of variation `null_delay_cv` (0: answer at once;
  // animat-worker --null-delay-ms). False, having said why on stderr, when
  // one cannot start, exits (a refused worker exits 3) or they do not join
  // within 10 s.
  bool Spawn(int count, int threads, bool null_evaluation,
             double null_delay_ms = 0, double null_delay_cv = 0);

  // SIGTERM to every worker, serving the dispatcher meanwhile so goodbyes
  // are heard; SIGKILL to those still running after 5 s.
  void Stop();

 private:
  std::string binary_;
  std::string log_;
  Dispatcher* dispatcher_;
  LocalWorkers workers_;
};

}  // namespace animat::bench

#endif  // ANIMAT_BENCH_WORKER_PROCESSES_H_
