// The dispatcher's logic without its socket (docs/protocol.md): who is
// greeted, what is leased to whom and until when, what is retried, isolated
// or complete. A plain state machine on an injected Clock: the transport
// (dispatcher.h) hands it each decoded message and the passing of time, and
// it answers through an Outbox, so that it can be driven and tested without
// ZeroMQ.
//
// Work is leased: a worker silent for kLiveness heartbeat intervals, or a
// lease older than lease_ms, puts its individuals back in the queue.
// Results are idempotent by individual: the first valid one counts, late
// duplicates are ignored. Individuals that were on a dying worker are
// retried alone, so one genome that kills workers does not take others
// down with it; one whose leases ended without a result kMaxAttempts times
// is evaluated alone by the Isolation (isolation.h), and completed as
// CRASHED only if that evaluation crashes too.
//
// Not thread-safe: one thread calls every method.
#ifndef ANIMAT_MASTER_DISPATCH_LEASE_SCHEDULER_H_
#define ANIMAT_MASTER_DISPATCH_LEASE_SCHEDULER_H_

#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "animat/v1/protocol.pb.h"
#include "common/base/clock.h"
#include "common/base/log.h"
#include "common/protocol/genome_wire.h"
#include "common/protocol/protocol.h"
#include "master/dispatch/evaluation_service.h"
#include "master/dispatch/isolation.h"
#include "master/dispatch/work_encoder.h"

namespace animat {

// Where the scheduler's messages go: the transport's socket, or a test's
// record of them.
class Outbox {
 public:
  virtual ~Outbox() = default;
  // Hands `bytes` (an encoded Envelope) over for the peer `identity`.
  // False, with `problem` saying why, when it cannot be handed over (the
  // peer's queue is full, or the peer is gone).
  virtual bool Deliver(const std::string& identity, const std::string& bytes,
                       std::string* problem) = 0;
};

struct SchedulerOptions {
  // In [kMinHeartbeatMs, kMaxHeartbeatMs].
  int heartbeat_ms = protocol::kHeartbeatMs;
  // A lease not completed in this time (>= 1) goes back to the queue.
  int lease_ms = 10 * 60 * 1000;
  // Evaluates a suspect alone (not owned; must outlive the scheduler), or
  // null: DispatcherOptions::isolation.
  Isolation* isolation = nullptr;
  bool accept_null_workers = false;
  // DispatcherOptions::acknowledge_on_receipt.
  bool acknowledge_on_receipt = true;
  LogSink log = Prefixed("dispatcher", StderrSink);
  // DispatcherOptions::idle_notice_ms and notices (already defaulted to
  // `log` when empty).
  int idle_notice_ms = 30000;
  LogSink notices;
  // Not owned; must outlive the scheduler.
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

class LeaseScheduler {
 public:
  // Workers are welcomed with `model` (ConfigToProto). `outbox` is not
  // owned and must outlive the scheduler.
  LeaseScheduler(SchedulerOptions options, v1::Config model, Outbox* outbox);

  // The endpoint the transport listens on, for the idle notice.
  void set_endpoint(std::string endpoint) { endpoint_ = std::move(endpoint); }

  // A further model configuration to evaluate under, and the index to
  // submit under (the constructor's `model` is 0); one already added gives
  // its index again. A worker is sent each configuration in the first Work
  // of it that it gets (Work.config). Fails beyond protocol::kMaxConfigs.
  Result<size_t> AddConfig(const v1::Config& config);

  // Queues an individual, to be evaluated under configuration `config`
  // (an index AddConfig gave; 0: the constructor's); one already pending
  // is left as it is.
  void Submit(uint64_t individual, const protocol::SerializedGenome& genome,
              size_t config = 0);

  // One decoded message from the peer `identity`; completions it brings
  // are appended to `done`.
  void Handle(const std::string& identity, const v1::Envelope& envelope,
              std::vector<Completion>* done);
  // A Hello that did not decode (a field out of its limits, `why`): the
  // peer `name` (host:pid, as the Hello says) is refused saying why.
  void RefuseMalformed(const std::string& identity, const v1::Hello& hello,
                       const std::string& why);
  // A message the transport could not read: logged and counted.
  void Ignore(const std::string& what);
  // The greeted worker's name for `identity`, or "an unknown peer".
  std::string PeerName(const std::string& identity) const;

  // Leases queued work to workers with credit.
  void Dispatch();
  // What time decides: isolated evaluations that ended, silent workers,
  // expired leases, heartbeats due, the idle notice.
  void Housekeep(std::vector<Completion>* done);

  // Dispatcher::Acknowledge.
  void Acknowledge(const std::vector<uint64_t>& individuals);
  // A Goodbye with `reason` to every greeted worker.
  void Farewell(const std::string& reason);

  size_t pending() const { return pending_.size(); }
  bool IsPending(uint64_t individual) const {
    return pending_.count(individual) != 0;
  }
  size_t workers() const { return workers_.size(); }
  const DispatcherStats& stats() const { return stats_; }
  // Of configuration 0.
  uint64_t config_hash() const { return configs_[0].hash; }
  const Clock& clock() const { return *options_.clock; }

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
    // The configurations it has (the welcome's, those Work carried).
    std::set<size_t> configs;
  };

  struct Individual {
    std::string item;  // The serialised WorkItem (work_encoder.h).
    uint64_t genome_hash = 0;
    size_t config = 0;   // Index in configs_.
    uint64_t lease = 0;  // Serial of its current lease.
    int attempts = 0;
    bool leased = false;
    bool isolated = false;  // Being evaluated alone (options_.isolation).
    std::string worker;     // Identity, when leased.
    TimePoint deadline;
  };

  void Greet(const std::string& identity, const v1::Hello& hello,
             uint32_t envelope_version);
  // Why a hello is refused ("" when it is not).
  std::string Refusal(const v1::Hello& hello, uint32_t envelope_version) const;
  // Refuses the peer, saying why, and ends its session if it had one.
  void RefuseWorker(const std::string& identity, const std::string& name,
                    const std::string& refusal);
  void Collect(const std::string& identity, WorkerState& worker,
               const v1::Results& results, std::vector<Completion>* done);
  void Lease(const std::string& identity, WorkerState& worker,
             uint64_t individual, TimePoint deadline, WorkEncoder* work,
             std::vector<uint64_t>* items);
  // Ends an individual's lease (it stays pending).
  void Unlease(uint64_t individual);
  // Removes a queued individual from its queue.
  void Unqueue(uint64_t individual);
  // The idle notice, when it is due.
  void NoticeIdle(TimePoint now);
  // Back to the queue after a lease ended without a result; after
  // kMaxAttempts counted, to the isolation instead.
  void Requeue(uint64_t individual, bool counts_as_attempt);
  void Isolate(uint64_t individual);
  // The isolated evaluations that ended: completions, or suspects again.
  void CollectIsolated(std::vector<Completion>* done);
  // Completes a pending individual (no longer leased or queued):
  // `completion` holds all but its attempts.
  void Complete(Completion completion, std::vector<Completion>* done);
  void DropWorker(const std::string& identity, bool died);
  // True when the message was handed to the outbox.
  bool Send(const std::string& identity, v1::Envelope envelope);
  // The same for an encoded envelope; `what` names its body for the log.
  bool SendEncoded(const std::string& identity, const char* what,
                   const std::string& bytes);
  // Sends the work of `items`, all of configuration `config` (carried
  // when the worker does not have it yet); if it cannot be delivered, they
  // go back to the queue at once (no attempt counted) and false is
  // returned.
  bool SendWork(const std::string& identity, WorkerState& worker, size_t config,
                WorkEncoder* work, const std::vector<uint64_t>& items);

  struct Config {
    v1::Config message;
    uint64_t hash = 0;
    std::string bytes;  // Serialised, as Work.config carries it.
  };

  SchedulerOptions options_;
  std::vector<Config> configs_;  // [0]: the constructor's.
  Outbox* outbox_;
  std::string endpoint_;
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

#endif  // ANIMAT_MASTER_DISPATCH_LEASE_SCHEDULER_H_
