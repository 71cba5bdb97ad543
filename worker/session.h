// One session of a Worker with a master, from its hello to its end: the
// state machine of docs/protocol.md. Connecting (hello sent), serving once
// welcomed, stopping on Worker::Stop(), and lost when the master falls
// silent, or told by the master that its run is over. What outlives a session
// (the pool, results not yet sent or not yet acknowledged) is the Worker's,
// which the session borrows.
//
// Private to worker/. A Session and its Worker belong to the thread that
// runs Worker::Run(); only Worker::Stop() may come from elsewhere.
#ifndef ANIMAT_WORKER_SESSION_H_
#define ANIMAT_WORKER_SESSION_H_

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>
#include <zmq.hpp>

#include "animat/v1/protocol.pb.h"
#include "common/protocol/handshake_monitor.h"
#include "worker/evaluation_pool.h"
#include "worker/worker.h"

namespace animat {

class Worker::Session {
 public:
  // Connects a DEALER socket of `context` to the worker's master; `worker`
  // and `context` must outlive the session.
  Session(Worker& worker, zmq::context_t& context);

  // Says hello and serves until the session ends: Stop() (after the
  // goodbye), a refusal, or the master silent for kLiveness heartbeats.
  SessionEnd Run();

 private:
  // What the last wait found readable.
  struct Events {
    bool master = false;
    bool pool = false;
    bool handshake = false;
  };

  void SayHello();
  // Hands back the items not started; the evaluations under way finish.
  void BeginStopping();
  bool Drained() const { return !pool() || pool()->in_flight() == 0; }
  // The last results and the goodbye.
  void SayGoodbye();
  Events Wait();
  // Reads every message waiting; a refusal ends the session.
  std::optional<SessionEnd> Receive();
  std::optional<SessionEnd> Handle(const v1::Envelope& envelope);
  void Welcomed(const v1::Welcome& welcome);
  // The results the last master did not acknowledge, to this one.
  void SendUnacknowledged();
  void Accept(const v1::Work& work);
  Result<std::shared_ptr<const ModelConfig>> ConfigOf(const v1::Work& work);
  void CollectFinished();
  // Results finished since the last call, with the credit they earn.
  void SendResults();
  // Remembers a result sent until the master acknowledges it.
  void KeepUnacknowledged(const v1::WorkResult& result);
  void Send(const v1::Envelope& envelope);
  // Logs how handshakes with the master failed (CurveZMQ refusals).
  void ReadHandshakes();
  std::string HandshakeProblem(const protocol::HandshakeEvent& event) const;
  void SendCredit(int credit);
  // The master's goodbye: its run is over.
  SessionEnd RunOver(const v1::Goodbye& goodbye);
  SessionEnd Lost();
  // Milliseconds of options_.clock since `t`.
  int64_t MillisSince(Clock::TimePoint t) const;

  // The worker's: it outlives the session.
  std::unique_ptr<EvaluationPool>& pool() const { return worker_.pool_; }

  Worker& worker_;
  const WorkerOptions& options_;
  zmq::socket_t socket_;
  protocol::HandshakeMonitor handshakes_;  // Of socket_.
  Clock::TimePoint last_heard_;            // On options_.clock.
  Clock::TimePoint last_sent_;
  int heartbeat_ms_;
  bool welcomed_ = false;
  bool stopping_ = false;
  std::vector<uint64_t> returned_;  // Handed back, for the goodbye.
  int uncredited_ = 0;  // Results finished before this session's welcome.
  bool warned_unacknowledged_ = false;
  bool send_failed_ = false;  // A failed send was logged (once a session).
  // A handshake failure without detail, said if the session is lost and
  // nothing more precise was said.
  std::string unexplained_;
};

}  // namespace animat

#endif  // ANIMAT_WORKER_SESSION_H_
