// The master's dispatcher: hands individuals' genomes to workers over a
// ZeroMQ ROUTER socket and collects their evaluations (docs/protocol.md).
//
// Work is leased: a worker silent for kLiveness heartbeat intervals, or a
// lease older than lease_ms, puts its individuals back in the queue.
// Results are idempotent by individual: the first valid one counts, late
// duplicates are ignored. Individuals that were on a dying worker are
// retried alone, so one genome that kills workers does not take others
// down with it; one whose leases ended without a result kMaxAttempts times
// is evaluated alone by the Isolation (isolation.h), and completed as
// CRASHED only if that evaluation crashes too: a vanished worker is no
// evidence against a genome, so faults never decide a result. Malformed
// input of any kind is refused in one log line, peers' strings escaped
// and cut short, and survived.
//
// The model configuration travels as the protocol's message (v1::Config,
// made by ConfigToProto): the dispatcher never evaluates, so it does not
// link the simulator.
//
// Not thread-safe: one thread calls Submit and Poll.
#ifndef ANIMAT_MASTER_DISPATCH_DISPATCHER_H_
#define ANIMAT_MASTER_DISPATCH_DISPATCHER_H_

#include <chrono>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "animat/v1/protocol.pb.h"
#include "common/base/clock.h"
#include "common/base/log.h"
#include "common/base/status.h"
#include "common/protocol/genome_wire.h"
#include "common/protocol/protocol.h"
#include "master/dispatch/evaluation_service.h"
#include "master/dispatch/isolation.h"
#include "master/dispatch/work_encoder.h"

namespace zmq {
class context_t;
class socket_t;
}  // namespace zmq

namespace animat {

class HandshakeLog;
class ZapAuthenticator;

struct DispatcherOptions {
  std::string endpoint = "tcp://127.0.0.1:5555";  // Where to bind.
  // In [kMinHeartbeatMs, kMaxHeartbeatMs].
  int heartbeat_ms = protocol::kHeartbeatMs;
  // A lease not completed in this time (>= 1) goes back to the queue.
  int lease_ms = 10 * 60 * 1000;
  // Evaluates a suspect alone after kMaxAttempts leases ended without a
  // result (not owned; it must outlive the dispatcher). Null: such a
  // suspect is retried on workers for ever, one lease at a time.
  Isolation* isolation = nullptr;
  // Accept workers in null-evaluation mode (dispatch benchmarks only).
  bool accept_null_workers = false;
  // CurveZMQ (docs/security.md): this master's secret key (Z85) and the
  // worker public keys it serves (Z85 -> name for the log). With a key,
  // every connection is encrypted and only listed workers get through.
  // An endpoint beyond loopback requires a key unless `insecure`.
  std::string curve_secret_key;
  std::map<std::string, std::string> curve_allowed;
  // Bind beyond loopback without CurveZMQ (trusted networks only; warns).
  bool insecure = false;
  // Results are acknowledged to their worker (which then forgets them) as
  // they arrive. A master that records results sets this to false and
  // calls Acknowledge once they are committed: a worker then sends a
  // result again to the next master if this one dies before that.
  bool acknowledge_on_receipt = true;
  LogSink log = Prefixed("dispatcher", StderrSink);
  // While no worker is connected, a line every this many ms (of the
  // clock) says so, with the endpoint listened on ("no worker has joined
  // in 30 s; listening on tcp://..."); 0: never. It goes to `notices`, or
  // to `log` when `notices` is empty (a master whose routine log is off
  // still says so).
  int idle_notice_ms = 30000;
  LogSink notices;
  // The time heartbeats, liveness and leases are kept by (not owned; it
  // must outlive the dispatcher). Tests give a ManualClock: then Poll(0)
  // makes one pass, and a longer Poll returns only with completions or
  // once another thread has moved the clock past its timeout.
  const Clock* clock = &RealClock();
};

struct DispatcherStats {
  int64_t dispatched = 0;  // Items sent (re-sends counted again).
  int64_t completed = 0;   // Individuals completed with a result.
  int64_t isolated = 0;    // Evaluations of a suspect alone started.
  int64_t crashed = 0;     // Individuals completed as CRASHED.
  int64_t requeued = 0;    // Leases returned to the queue.
  int64_t ignored = 0;     // Messages or results ignored (logged).
  int64_t refused = 0;     // Workers refused.
};

class Dispatcher final : public EvaluationService {
 public:
  // Checks the options (CurveZMQ keys, an endpoint beyond loopback) and
  // binds the socket: fails, saying why, without binding when they are
  // wrong, and with kIoError when the endpoint cannot be bound (port in
  // use). Workers are welcomed with `model`, the model configuration they
  // evaluate by (ConfigToProto). `context` must outlive the dispatcher.
  static Result<std::unique_ptr<Dispatcher>> Create(zmq::context_t* context,
                                                    DispatcherOptions options,
                                                    v1::Config model);
  ~Dispatcher() override;

  // What Create refuses before binding: an endpoint beyond loopback without
  // CurveZMQ keys (unless `insecure`), or keys of the wrong form; a
  // message that says what to give instead.
  static Status CheckOptions(const DispatcherOptions& options);

  // Queues an individual for evaluation; an individual already pending is
  // left as it is. The genome must be valid.
  void Submit(uint64_t individual, const v1::Genome& genome) override;
  // The same with the genome serialised (protocol::SerializeGenome), as
  // the caller may already have it.
  void Submit(uint64_t individual,
              const protocol::SerializedGenome& genome) override;

  // Serves workers for up to `timeout_ms` (of the clock's time) and returns
  // the completions that came in, as soon as there are some.
  std::vector<Completion> Poll(int timeout_ms) override;

  // Tells every connected worker that the run is over (a Goodbye with
  // `reason`; docs/protocol.md), so that workers started to serve it may
  // exit. The messages are delivered before the dispatcher is destroyed
  // (up to a second's wait then).
  void Farewell(const std::string& reason);

  // Tells the workers that delivered these completions' results that they
  // may forget them (with acknowledge_on_receipt off; otherwise, and for
  // individuals not completed here or already acknowledged, nothing). A
  // worker that has gone since is not told; it sends the result again to
  // the next master, which ignores it once recorded.
  void Acknowledge(const std::vector<uint64_t>& individuals) override;

  // Individuals submitted and not completed.
  size_t pending() const override { return pending_.size(); }
  // Workers currently greeted.
  size_t workers() const { return workers_.size(); }
  const DispatcherStats& stats() const { return stats_; }
  uint64_t config_hash() const { return config_hash_; }
  // The endpoint actually bound ("tcp://127.0.0.1:41234" for a ":*" port).
  const std::string& endpoint() const { return endpoint_; }
  // DispatcherOptions::clock.
  const Clock& clock() const override { return *options_.clock; }

 private:
  using TimePoint = Clock::TimePoint;

  struct WorkerState {
    std::string name;       // host:pid
    uint64_t instance = 0;  // Hello.instance; 0 when none was given.
    int threads = 1;
    int credit = 0;
    bool null_evaluation = false;
    TimePoint last_heard;
    TimePoint last_sent;
    bool send_failed = false;  // The last send failed (logged once).
    std::set<uint64_t> leased;
    std::optional<uint64_t> suspect;  // The suspect it holds alone.
  };
  struct Individual {
    std::string item;  // The serialised WorkItem (work_encoder.h).
    uint64_t genome_hash = 0;
    uint64_t lease = 0;  // Serial of its current lease.
    int attempts = 0;
    bool leased = false;
    bool isolated = false;  // Being evaluated alone (options_.isolation).
    std::string worker;     // Identity, when leased.
    TimePoint deadline;
  };

  Dispatcher(zmq::context_t* context, DispatcherOptions options,
             v1::Config model);

  void Receive(std::vector<Completion>* done);
  void Handle(const std::string& identity, const v1::Envelope& envelope,
              std::vector<Completion>* done);
  void Greet(const std::string& identity, const v1::Hello& hello,
             uint32_t envelope_version);
  // Why a hello is refused ("" when it is not).
  std::string Refusal(const v1::Hello& hello, uint32_t envelope_version) const;
  // Refuses the peer, saying why, and ends its session if it had one.
  void RefuseWorker(const std::string& identity, const std::string& name,
                    const std::string& refusal);
  // A frame that failed to decode (`why`) but is a Hello (a field out of
  // its limits): the peer is refused saying why. False when it is not.
  bool RefuseMalformedHello(const std::string& identity, const void* data,
                            size_t size, const std::string& why);
  void Collect(const std::string& identity, WorkerState& worker,
               const v1::Results& results, std::vector<Completion>* done);
  void Dispatch();
  void Lease(const std::string& identity, WorkerState& worker,
             uint64_t individual, TimePoint deadline, WorkEncoder* work,
             std::vector<uint64_t>* items);
  // Ends an individual's lease (it stays pending).
  void Unlease(uint64_t individual);
  // Removes a queued individual from its queue.
  void Unqueue(uint64_t individual);
  void Housekeep(std::vector<Completion>* done);
  // The idle notice, when it is due.
  void NoticeIdle(TimePoint now);
  // Back to the queue after a lease ended without a result; after
  // kMaxAttempts counted, to the isolation instead.
  void Requeue(uint64_t individual, bool counts_as_attempt);
  void Isolate(uint64_t individual);
  // The isolated evaluations that ended: completions, or suspects again.
  void CollectIsolated(std::vector<Completion>* done);
  // Completes a pending individual (no longer leased or queued) with
  // `result`, evaluated by `evaluator`.
  void Complete(uint64_t individual, v1::EvaluationResult result,
                std::string evaluator, double wall_seconds,
                bool null_evaluation, std::vector<Completion>* done);
  void DropWorker(const std::string& identity, bool died);
  // True when the message was handed to the socket.
  bool Send(const std::string& identity, v1::Envelope envelope);
  // The same for an encoded envelope; `what` names its body for the log.
  bool SendEncoded(const std::string& identity, const char* what,
                   const std::string& bytes);
  // Sends the work of `items`; if it cannot be delivered, they go back to
  // the queue at once (no attempt counted) and false is returned.
  bool SendWork(const std::string& identity, WorkerState& worker,
                WorkEncoder* work, const std::vector<uint64_t>& items);
  void Ignore(const std::string& what);

  DispatcherOptions options_;
  std::string endpoint_;
  v1::Config config_;
  uint64_t config_hash_;
  // Declared before the socket: destroyed after it (ZAP outlives it).
  std::unique_ptr<ZapAuthenticator> zap_;
  std::unique_ptr<zmq::socket_t> socket_;
  // Handshakes that fail on socket_ (destroyed before it).
  std::unique_ptr<HandshakeLog> handshakes_;
  std::map<uint64_t, Individual> pending_;
  std::deque<uint64_t> queue_;  // Queued individuals, next first.
  // Queued after a failed attempt, by most attempts first (so failures
  // are decided quickly), then individual: (-attempts, individual).
  std::set<std::pair<int, uint64_t>> suspects_;
  std::string drainer_;  // The worker emptying itself for a suspect.
  // Leases in the order made (their deadlines are non-decreasing); a record
  // whose lease already ended is skipped when it reaches the front.
  struct LeaseRecord {
    TimePoint deadline;
    uint64_t individual;
    uint64_t lease;
  };
  std::deque<LeaseRecord> lease_order_;
  uint64_t leases_made_ = 0;
  std::map<std::string, WorkerState> workers_;
  // Completions not yet acknowledged (acknowledge_on_receipt off): the
  // identity that delivered each one's result.
  std::map<uint64_t, std::string> delivered_;
  std::set<std::string> strangers_;  // Unknown identities already logged.
  bool ever_joined_ = false;
  TimePoint idle_since_;   // When the last worker left (or the start).
  TimePoint last_notice_;  // Of the idle notice.
  DispatcherStats stats_;
};

}  // namespace animat

#endif  // ANIMAT_MASTER_DISPATCH_DISPATCHER_H_
