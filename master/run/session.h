// The one start-up path of a master, shared by animat-master and `animat
// evolve`: checks the request (configuration, keys, endpoint) before the
// store is touched, installs the SIGTERM/SIGINT handlers, opens the store,
// plans the run (start or resume; read only), binds the dispatcher, then
// writes the run, starts the local workers if asked, runs it with progress
// reports and says how to continue it. A start-up that fails before the
// run is written (a port in use, a bad key file) leaves the store as it
// was (docs/master.md).
//
// Runs on the calling thread; one session per process (the signal
// handlers are the process's).
#ifndef ANIMAT_MASTER_RUN_SESSION_H_
#define ANIMAT_MASTER_RUN_SESSION_H_

#include <atomic>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/base/log.h"
#include "common/base/status.h"
#include "common/protocol/protocol.h"
#include "master/dispatch/dispatcher.h"
#include "master/run/evolution_run.h"
#include "master/run/local_workers.h"

namespace animat {

enum class RunChoice {
  kStart,          // A new run: the store must hold none.
  kResume,         // The store's run: the store must exist and hold one.
  kStartOrResume,  // The store's run if it holds one, else a new run.
};

// Writes the line and a newline to standard output and flushes it, as a
// program's result (no timestamp). Callable from any thread.
void StdoutSink(std::string_view line);

struct SessionOptions {
  // What to run: the run configuration file (needed to start; when
  // resuming, it must match the run's unless `force`), the lineage store,
  // and the number of generations in all (extends a finished run; fewer
  // than the run has made is refused).
  std::string config_path;
  std::string db_path;
  RunChoice choice = RunChoice::kStart;
  bool force = false;
  std::optional<int> generations;

  // Where and how workers connect (docs/security.md): the endpoint to
  // bind, the heartbeat, CurveZMQ key files (the master's key pair, the
  // allowed workers' keys) or, beyond loopback without keys, `insecure`.
  std::string bind = "tcp://127.0.0.1:5555";
  int heartbeat_ms = protocol::kHeartbeatMs;
  std::string curve_secret_file;
  std::string curve_allow_file;
  bool insecure = false;

  // animat-worker processes of one thread each to start beside the master
  // once it listens (the animat-worker beside this program), their output
  // appended to `worker_log`.
  int local_workers = 0;
  std::string worker_log;

  // The command that continues the run, without --generations (e.g.
  // "animat-master --resume --db run.db --bind ..."): said when the run
  // stops before its end, and in the refusal of too few generations.
  std::string resume_command;

  // Where the session speaks. Progress and diagnostics are log lines
  // (timestamped, on standard error by default); `outcome` is the one line
  // that ends the session (finished, or the command that resumes it), the
  // program's result, on standard output by default so that it can be
  // piped or captured apart from the log.
  LogSink log = Prefixed("master", StderrSink);  // The session's.
  LogSink dispatcher_log = Prefixed("dispatcher", StderrSink);  // Workers'.
  LogSink outcome = StdoutSink;
  // After each generation completes; the programs log a progress line.
  std::function<void(const GenerationReport&)> progress;
};

// `words` as one POSIX shell command line, each word quoted when it needs
// to be ("animat-master --db 'my run.db'"), for the hints a session gives.
std::string CommandLine(const std::vector<std::string>& words);

// From here on SIGTERM and SIGINT set the flag returned (the process's
// one), so that whoever serves a run stops it cleanly, whenever they come.
const std::atomic<bool>& InstallStopHandlers();

// The dispatcher's options for `o` (bind, heartbeat, keys, insecure, the
// logs; results acknowledged once recorded), the key files read and the
// endpoint checked; errors say what to give instead.
Result<DispatcherOptions> ListenOptions(const SessionOptions& o);

// A local worker without a master for this long (its master was killed
// with SIGKILL) exits, seconds.
inline constexpr int kLocalWorkerIdleTimeoutS = 60;

// Starts o.local_workers animat-worker processes (beside this program, one
// thread each, exiting when the run is over, or kLocalWorkerIdleTimeoutS
// after their master vanished) connecting to `dispatcher`,
// their output appended to o.worker_log; none when it is 0.
Status StartLocalWorkers(const SessionOptions& o, const Dispatcher& dispatcher,
                         LocalWorkers* workers);

// Runs the session to the run's end, or until SIGTERM or SIGINT (then
// what came in is committed and the store is left resumable). Errors say
// what is wrong, for the program to print (exit 1).
Status RunSession(const SessionOptions& options);

}  // namespace animat

#endif  // ANIMAT_MASTER_RUN_SESSION_H_
