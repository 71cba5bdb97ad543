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
#include "master/dispatch/lease_scheduler.h"

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

class Dispatcher final : public MultiConfigService, private Outbox {
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

  // Further model configurations (LeaseScheduler::AddConfig): individuals
  // submitted under one are evaluated under it; at most
  // protocol::kMaxConfigs, the welcome's included.
  Result<size_t> AddConfig(const v1::Config& config) override {
    return scheduler_.AddConfig(config);
  }
  void SubmitUnder(size_t config, uint64_t individual,
                   const protocol::SerializedGenome& genome) override {
    scheduler_.Submit(individual, genome, config);
  }

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
  size_t pending() const override { return scheduler_.pending(); }
  // Workers currently greeted.
  size_t workers() const { return scheduler_.workers(); }
  const DispatcherStats& stats() const { return scheduler_.stats(); }
  uint64_t config_hash() const { return scheduler_.config_hash(); }
  // The endpoint actually bound ("tcp://127.0.0.1:41234" for a ":*" port).
  const std::string& endpoint() const { return endpoint_; }
  // DispatcherOptions::clock.
  const Clock& clock() const override { return *options_.clock; }

 private:
  Dispatcher(zmq::context_t* context, DispatcherOptions options,
             v1::Config model);
  // Reads what the socket holds and hands each decoded message to the
  // scheduler.
  void Receive(std::vector<Completion>* done);
  // A frame that failed to decode (`why`) but is a Hello (a field out of
  // its limits): the peer is refused saying why. False when it is not.
  bool RefuseMalformedHello(const std::string& identity, const void* data,
                            size_t size, const std::string& why);
  // Outbox: the socket, without waiting.
  bool Deliver(const std::string& identity, const std::string& bytes,
               std::string* problem) override;

  DispatcherOptions options_;
  std::string endpoint_;
  // Declared before the socket: destroyed after it (ZAP outlives it).
  std::unique_ptr<ZapAuthenticator> zap_;
  std::unique_ptr<zmq::socket_t> socket_;
  // Handshakes that fail on socket_ (destroyed before it).
  std::unique_ptr<HandshakeLog> handshakes_;
  LeaseScheduler scheduler_;
};

}  // namespace animat

#endif  // ANIMAT_MASTER_DISPATCH_DISPATCHER_H_
