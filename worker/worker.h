// An evaluation worker: connects to a master, says hello, receives the
// configuration and work, evaluates with a pool of threads, returns
// results, and keeps going across master restarts (docs/protocol.md).
//
// Stateless: everything it knows comes from the current session. Run()
// and the constructor belong to one thread; Stop() may be called from any
// thread or a signal handler.
#ifndef ANIMAT_WORKER_WORKER_H_
#define ANIMAT_WORKER_WORKER_H_

#include <atomic>
#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "animat/v1/protocol.pb.h"
#include "common/base/clock.h"
#include "common/base/log.h"
#include "common/protocol/protocol.h"
#include "worker/config_cache.h"
#include "worker/null_delay.h"

namespace zmq {
class context_t;
class socket_t;
}  // namespace zmq

namespace animat {

class EvaluationPool;

struct WorkerOptions {
  std::string endpoint;  // The master's, e.g. "tcp://127.0.0.1:5555".
  int threads = 1;       // Evaluations at once (>= 1).
  // Simulate nothing and answer every item at once (dispatch benchmarks);
  // the master must accept such workers explicitly.
  bool null_evaluation = false;
  // How long each null evaluation takes (null_delay.h); none by default.
  NullDelay null_delay;
  // Heartbeat interval until the master's Welcome sets its own.
  int heartbeat_ms = protocol::kHeartbeatMs;
  // Reconnection backoff after the master falls silent: doubles from min
  // to max.
  int reconnect_min_ms = protocol::kReconnectMinMs;
  int reconnect_max_ms = protocol::kReconnectMaxMs;
  // CurveZMQ (docs/security.md): the master's public key and this worker's
  // key pair, Z85. All empty: a plain connection (loopback or --insecure
  // masters only); all set: an encrypted one the master must allow.
  std::string curve_server_key;
  std::string curve_public_key;
  std::string curve_secret_key;
  // When the master says its run is over (docs/protocol.md): exit (Run
  // returns kExitDone) instead of waiting for a next master.
  bool exit_when_done = false;
  // Exit (kExitDone) once no master has welcomed this worker for this many
  // seconds (checked between connection attempts); 0: never.
  int idle_timeout_s = 0;
  // Log every work message received: its individuals and how many items
  // the pool then holds (one line per message; for following a worker).
  bool log_items = false;
  LogSink log = Prefixed("worker", StderrSink);
  // The time heartbeats, the master's liveness and the idle timeout are
  // kept by (a ManualClock in tests); it must outlive the worker. Waits
  // are real time, at most 100 ms at once, so a move of the clock takes
  // effect within one wait.
  const Clock* clock = &RealClock();
};

class Worker {
 public:
  // Exit codes of Run().
  static constexpr int kExitStopped = 0;  // Stop() was called.
  static constexpr int kExitDone = 0;     // The run is over, or no master came.
  static constexpr int kExitBadEndpoint = 2;  // ZeroMQ refused the endpoint.
  static constexpr int kExitRefused = 3;      // The master refused us.

  explicit Worker(WorkerOptions options);
  ~Worker();

  // Serves masters until Stop(), a refusal, or (as the options say) the end
  // of the run or a long time without a master.
  int Run();

  // Asks Run() to hand back the work it has not started, finish the
  // evaluations under way, send their results and a goodbye, and return.
  // Async-signal-safe.
  void Stop() { stop_.store(true, std::memory_order_relaxed); }

 private:
  // kLost: the master fell silent (kLostAfterWelcome: after welcoming us,
  // so the backoff starts again from its minimum); kRunOver: the master
  // said its run is over.
  enum class SessionEnd {
    kStopped,
    kRefused,
    kLost,
    kLostAfterWelcome,
    kRunOver
  };
  // The next session's end; kExitBadEndpoint when ZeroMQ refuses the
  // endpoint.
  std::optional<SessionEnd> RunSession(zmq::context_t& context);
  // Waits `ms` before the next connection, or less when Stop() is called
  // or the idle timeout comes first.
  void Backoff(int ms, Clock::TimePoint idle_since);
  bool IdleTooLong(Clock::TimePoint idle_since) const;
  // One connection to a master, from its hello to its end (session.h).
  class Session;

  WorkerOptions options_;
  std::string host_;
  // Hello.instance: random, fixed for the life of this object, so the
  // master knows a reconnection from a new worker. Not a draw that reaches
  // results.
  uint64_t instance_ = 0;
  std::atomic<bool> stop_{false};
  // Survives sessions, so evaluations under way when a master vanished
  // finish and are offered to the next one.
  std::unique_ptr<EvaluationPool> pool_;
  // The configurations masters gave (survives sessions too).
  ConfigCache configs_;
  // Finished results not yet sent (waiting for a welcome).
  std::vector<v1::WorkResult> unsent_;
  // Results sent and not yet acknowledged by the master, by individual:
  // sent again to the next master that welcomes this worker, so none is
  // lost when a master dies before recording it. At most
  // kMaxUnacknowledged (a master that never acknowledges is not followed
  // further; logged).
  std::map<uint64_t, v1::WorkResult> unacknowledged_;
  // The last handshake failure logged (a sentence; "" after a handshake
  // succeeded), so a failure that repeats at every reconnection is said
  // once.
  std::string handshake_problem_;
};

}  // namespace animat

#endif  // ANIMAT_WORKER_WORKER_H_
