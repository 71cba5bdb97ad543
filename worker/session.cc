#include "worker/session.h"

#include <unistd.h>

#include <algorithm>
#include <map>
#include <string>
#include <utility>

#include "common/base/text.h"
#include "common/evaluation/model_config.h"
#include "common/protocol/genome_wire.h"
#include "common/protocol/protocol.h"
#include "common/protocol/zmq_poll.h"

namespace animat {
namespace {

// Results kept for a next master at most (a few hundred bytes each).
constexpr size_t kMaxUnacknowledged = 100000;

}  // namespace

Worker::Session::Session(Worker& worker, zmq::context_t& context)
    : worker_(worker),
      options_(worker.options_),
      socket_(context, zmq::socket_type::dealer),
      handshakes_(context, socket_),
      heartbeat_ms_(worker.options_.heartbeat_ms) {
  socket_.set(zmq::sockopt::linger, 0);
  socket_.set(zmq::sockopt::maxmsgsize, protocol::kMaxMessageBytes);
  if (!options_.curve_server_key.empty()) {
    socket_.set(zmq::sockopt::curve_serverkey, options_.curve_server_key);
    socket_.set(zmq::sockopt::curve_publickey, options_.curve_public_key);
    socket_.set(zmq::sockopt::curve_secretkey, options_.curve_secret_key);
  }
  socket_.connect(options_.endpoint);
  last_heard_ = options_.clock->Now();
  last_sent_ = options_.clock->Now();
}

Worker::SessionEnd Worker::Session::Run() {
  SayHello();
  for (;;) {
    if (worker_.stop_.load(std::memory_order_relaxed) && !stopping_) {
      if (!welcomed_) return SessionEnd::kStopped;
      BeginStopping();
    }
    if (stopping_ && Drained()) {
      SayGoodbye();
      return SessionEnd::kStopped;
    }
    const Events events = Wait();
    if (events.master) {
      if (std::optional<SessionEnd> end = Receive()) return *end;
    }
    if (events.handshake) ReadHandshakes();
    if (pool() && events.pool) CollectFinished();
    if (welcomed_ && !worker_.unsent_.empty()) SendResults();
    if (MillisSince(last_sent_) >= heartbeat_ms_) {
      v1::Envelope heartbeat;
      heartbeat.mutable_heartbeat();
      Send(heartbeat);
    }
    if (MillisSince(last_heard_) > protocol::kLiveness * heartbeat_ms_) {
      return Lost();
    }
  }
}

void Worker::Session::SayHello() {
  v1::Envelope hello;
  v1::Hello* h = hello.mutable_hello();
  h->set_protocol_version(protocol::kVersion);
  h->set_build_id(protocol::BuildId());
  h->set_threads(options_.threads);
  h->set_host(worker_.host_);
  h->set_pid(static_cast<uint64_t>(getpid()));
  h->set_null_evaluation(options_.null_evaluation);
  h->set_instance(worker_.instance_);
  Send(hello);
}

void Worker::Session::BeginStopping() {
  stopping_ = true;
  returned_ = pool() ? pool()->Abandon() : std::vector<uint64_t>{};
  options_.log("stopping: handing back " + std::to_string(returned_.size()) +
               " items, finishing " +
               std::to_string(pool() ? pool()->in_flight() : 0));
}

void Worker::Session::SayGoodbye() {
  std::vector<v1::WorkResult>& unsent = worker_.unsent_;
  if (pool()) {
    for (v1::WorkResult& r : pool()->TakeFinished()) {
      unsent.push_back(std::move(r));
    }
  }
  // In messages of up to kMaxBatch, without credit (stopping).
  if (!unsent.empty()) SendResults();
  v1::Envelope goodbye;
  for (uint64_t id : returned_) goodbye.mutable_goodbye()->add_returned(id);
  goodbye.mutable_goodbye()->set_reason("worker stopping");
  Send(goodbye);
}

Worker::Session::Events Worker::Session::Wait() {
  zmq::pollitem_t items[3] = {
      {static_cast<void*>(socket_), 0, ZMQ_POLLIN, 0},
      {handshakes_.handle(), 0, ZMQ_POLLIN, 0},
      {nullptr, pool() ? pool()->wakeup_fd() : -1, ZMQ_POLLIN, 0}};
  // The monitor, then the pool, when there are.
  int count = 1;
  if (items[1].socket != nullptr) ++count;
  if (pool()) items[count++] = items[2];
  const long timeout =
      std::max<long>(1, std::min<long>(heartbeat_ms_ - MillisSince(last_sent_),
                                       stopping_ ? 20 : 100));
  protocol::Poll(items, count, std::chrono::milliseconds(timeout));
  Events events;
  events.master = (items[0].revents & ZMQ_POLLIN) != 0;
  for (int i = 1; i < count; ++i) {
    if ((items[i].revents & ZMQ_POLLIN) == 0) continue;
    if (items[i].socket != nullptr) {
      events.handshake = true;
    } else {
      events.pool = true;
    }
  }
  return events;
}

std::optional<Worker::SessionEnd> Worker::Session::Receive() {
  zmq::message_t frame;
  while (socket_.recv(frame, zmq::recv_flags::dontwait)) {
    if (frame.more()) {
      // A multi-frame message is not ours: drain and drop it.
      options_.log("ignored a multi-frame message from the master");
      while (frame.more() && socket_.recv(frame, zmq::recv_flags::dontwait)) {
      }
      continue;
    }
    Result<v1::Envelope> decoded = protocol::Decode(frame.to_string_view());
    if (!decoded.ok()) {
      options_.log("ignored a malformed message from the master: " +
                   decoded.status().message());
      continue;
    }
    last_heard_ = options_.clock->Now();
    if (std::optional<SessionEnd> end = Handle(*decoded)) return end;
  }
  return std::nullopt;
}

std::optional<Worker::SessionEnd> Worker::Session::Handle(
    const v1::Envelope& envelope) {
  switch (envelope.body_case()) {
    case v1::Envelope::kWelcome:
      Welcomed(envelope.welcome());
      break;
    case v1::Envelope::kRefuse:
      options_.log(
          "refused by the master: " +
          ForeignText(envelope.refuse().reason(), protocol::kMaxReasonBytes));
      return SessionEnd::kRefused;
    case v1::Envelope::kWork:
      Accept(envelope.work());
      break;
    case v1::Envelope::kHeartbeat:
      break;
    case v1::Envelope::kAcknowledge:
      for (uint64_t id : envelope.acknowledge().individuals()) {
        worker_.unacknowledged_.erase(id);
      }
      break;
    case v1::Envelope::kGoodbye:
      return RunOver(envelope.goodbye());
    default:
      options_.log(std::string("ignored an unexpected ") +
                   protocol::BodyName(envelope) + " from the master");
      break;
  }
  return std::nullopt;
}

void Worker::Session::Welcomed(const v1::Welcome& welcome) {
  Result<std::shared_ptr<const ModelConfig>> config =
      worker_.configs_.Put(welcome.config(), welcome.config_hash());
  if (!config.ok()) {
    options_.log("ignored a welcome with a bad configuration: " +
                 config.status().message());
    return;
  }
  welcomed_ = true;
  // In [kMinHeartbeatMs, kMaxHeartbeatMs] (Decode checked it): kLiveness
  // times it fits an int.
  heartbeat_ms_ = static_cast<int>(welcome.heartbeat_ms());
  if (!pool()) {
    pool() = std::make_unique<EvaluationPool>(
        options_.threads, options_.null_evaluation, options_.null_delay);
  }
  options_.log("welcomed by " + options_.endpoint + " (" +
               std::to_string(options_.threads) + " threads)");
  SendCredit(options_.threads * protocol::kPrefetch - pool()->in_flight());
  uncredited_ = static_cast<int>(worker_.unsent_.size());
  SendUnacknowledged();
}

void Worker::Session::SendUnacknowledged() {
  const std::map<uint64_t, v1::WorkResult>& kept = worker_.unacknowledged_;
  if (kept.empty()) return;
  // The last master may have died before recording them; this one takes
  // those it still needs (they earn no credit: they were counted in the
  // session that ran them).
  options_.log("sending again " + std::to_string(kept.size()) +
               " results not acknowledged by the last master");
  v1::Envelope results;
  for (const auto& [id, result] : kept) {
    *results.mutable_results()->add_results() = result;
    if (results.results().results_size() == protocol::kMaxBatch) {
      Send(results);
      results.mutable_results()->clear_results();
    }
  }
  if (results.results().results_size() > 0) Send(results);
}

// The configuration `work` is to be evaluated under: the one it carries
// (checked and kept), or one kept before; an error saying why when
// neither.
Result<std::shared_ptr<const ModelConfig>> Worker::Session::ConfigOf(
    const v1::Work& work) {
  if (work.has_config()) {
    return worker_.configs_.Put(work.config(), work.config_hash());
  }
  std::shared_ptr<const ModelConfig> kept =
      worker_.configs_.Get(work.config_hash());
  if (kept) return kept;
  char hash[17];
  std::snprintf(hash, sizeof(hash), "%016llx",
                static_cast<unsigned long long>(work.config_hash()));
  return Status::NotFound(std::string("configuration ") + hash +
                          " was never given to this worker, or forgotten");
}

void Worker::Session::Accept(const v1::Work& work) {
  if (!welcomed_) {
    options_.log("ignored work before a welcome");
    return;
  }
  Result<std::shared_ptr<const ModelConfig>> config = ConfigOf(work);
  if (!config.ok()) {
    // Left out, their credit given back: the master's count of this
    // worker's credit stays right, and its leases expire.
    options_.log("ignored " + std::to_string(work.items_size()) +
                 " work items from the master: " + config.status().message());
    if (stopping_) {
      for (const v1::WorkItem& item : work.items()) {
        returned_.push_back(item.individual());  // Handed back.
      }
    } else if (work.items_size() > 0) {
      SendCredit(work.items_size());
    }
    return;
  }
  // An item out of the limits is left out, its credit given back: the
  // others are evaluated, and the master's count of this worker's credit
  // stays right.
  int left_out = 0;
  std::string received;  // The individuals taken, for --log-items.
  for (int i = 0; i < work.items_size(); ++i) {
    const v1::WorkItem& item = work.items(i);
    const Status valid = protocol::CheckWorkItem(item, i);
    if (!valid.ok()) {
      options_.log("ignored a work item from the master: " + valid.message());
      ++left_out;
      continue;
    }
    if (options_.log_items) {
      received.push_back(' ');
      received += std::to_string(item.individual());
    }
    if (stopping_) {
      returned_.push_back(item.individual());  // Handed back.
    } else {
      pool()->Submit(item, *config);
    }
  }
  if (options_.log_items && !received.empty()) {
    std::string line = "received";
    line += received;
    if (stopping_) {
      line += " (stopping: handed back)";
    } else {
      line += "; ";
      line += std::to_string(pool()->in_flight());
      line += " queued or running";
    }
    options_.log(line);
  }
  if (left_out > 0 && !stopping_) SendCredit(left_out);
}

void Worker::Session::CollectFinished() {
  for (v1::WorkResult& r : pool()->TakeFinished()) {
    worker_.unsent_.push_back(std::move(r));
  }
}

void Worker::Session::SendResults() {
  // Results wait in unsent_ for a session that welcomed us; a new master
  // takes those it still needs and ignores the rest.
  std::vector<v1::WorkResult> done;
  done.swap(worker_.unsent_);
  for (size_t begin = 0; begin < done.size(); begin += protocol::kMaxBatch) {
    v1::Envelope results;
    const size_t end = std::min(done.size(), begin + protocol::kMaxBatch);
    for (size_t i = begin; i < end; ++i) {
      KeepUnacknowledged(done[i]);
      *results.mutable_results()->add_results() = std::move(done[i]);
    }
    Send(results);
  }
  // Results that finished before the welcome were not in flight when its
  // credit was counted: they earn none now.
  const int earned = static_cast<int>(done.size()) - uncredited_;
  uncredited_ = std::max(0, uncredited_ - static_cast<int>(done.size()));
  if (!stopping_) SendCredit(earned);
}

void Worker::Session::KeepUnacknowledged(const v1::WorkResult& result) {
  std::map<uint64_t, v1::WorkResult>& kept = worker_.unacknowledged_;
  if (kept.size() < kMaxUnacknowledged) {
    kept[result.individual()] = result;
  } else if (!warned_unacknowledged_) {
    warned_unacknowledged_ = true;
    options_.log("the master has not acknowledged " +
                 std::to_string(kMaxUnacknowledged) +
                 " results; no more are kept for a next master");
  }
}

void Worker::Session::Send(const v1::Envelope& envelope) {
  const std::string bytes = protocol::Encode(envelope);
  const zmq::send_result_t sent =
      socket_.send(zmq::buffer(bytes), zmq::send_flags::dontwait);
  if (!sent && !send_failed_) {
    // Once a session: without a connection every heartbeat would fail.
    send_failed_ = true;
    options_.log(std::string("could not send ") + protocol::BodyName(envelope) +
                 " (no connection to " + options_.endpoint +
                 " yet; said once a session)");
  }
  last_sent_ = options_.clock->Now();
}

void Worker::Session::ReadHandshakes() {
  using Kind = protocol::HandshakeEvent::Kind;
  for (protocol::HandshakeEvent event : handshakes_.Read()) {
    if (event.kind == Kind::kFailed && event.code == 0 &&
        options_.curve_server_key.empty()) {
      // A worker without keys meets a handshake failure without detail
      // from a master that requires CurveZMQ and closed the connection
      // before this side read the master's mechanism (a race that load
      // decides): the mismatch, said as such, once.
      event.kind = Kind::kMechanismMismatch;
    }
    std::string& said = worker_.handshake_problem_;
    if (event.kind == Kind::kSucceeded) {
      said.clear();
    } else if (event.kind == Kind::kFailed) {
      // No detail: often the echo of a refusal the master made first
      // (its side of a mismatch). Said when the session ends, if nothing
      // more precise was (Lost).
      unexplained_ = HandshakeProblem(event);
    } else if (const std::string problem = HandshakeProblem(event);
               problem != said) {
      options_.log(problem);
      said = problem;
    }
  }
}

std::string Worker::Session::HandshakeProblem(
    const protocol::HandshakeEvent& event) const {
  using Kind = protocol::HandshakeEvent::Kind;
  const bool curve = !options_.curve_server_key.empty();
  const std::string master = "the master at " + options_.endpoint;
  switch (event.kind) {
    case Kind::kSucceeded:
      return "";
    case Kind::kRefusedKey:
      return master + " refused this worker's key " +
             options_.curve_public_key + " (CurveZMQ authentication, status " +
             std::to_string(event.code) +
             "): it must be on the master's allow-list (--curve-allow)";
    case Kind::kMechanismMismatch:
      return curve ? master +
                         " does not use CurveZMQ: start it with --curve-secret "
                         "and --curve-allow, or this worker without keys"
                   : master +
                         " requires CurveZMQ and refused this worker, which "
                         "has no keys: give it --curve-server (the master's "
                         "public key) and --curve-secret (docs/security.md)";
    default:
      // With keys, ZeroMQ gives no detail both when the server key is
      // wrong and when a master without CurveZMQ closes first: both said.
      return curve ? "the CurveZMQ handshake with " + master +
                         " failed: is --curve-server the master's public "
                         "key? If it is, the master does not use CurveZMQ "
                         "(the master's log says which)"
                   : "the handshake with " + master + " failed (ZeroMQ error " +
                         std::to_string(event.code) + ")";
  }
}

void Worker::Session::SendCredit(int credit) {
  if (credit <= 0) return;
  v1::Envelope envelope;
  envelope.mutable_credit()->set_credit(credit);
  Send(envelope);
}

Worker::SessionEnd Worker::Session::RunOver(const v1::Goodbye& goodbye) {
  // Nothing it holds is of use any more: the work not started, the
  // results not sent or not acknowledged.
  options_.log("the master's run is over (" +
               ForeignText(goodbye.reason(), protocol::kMaxReasonBytes) + ")");
  if (pool()) pool()->Abandon();
  worker_.unsent_.clear();
  worker_.unacknowledged_.clear();
  return SessionEnd::kRunOver;
}

int64_t Worker::Session::MillisSince(Clock::TimePoint t) const {
  return std::chrono::duration_cast<std::chrono::milliseconds>(
             options_.clock->Now() - t)
      .count();
}

Worker::SessionEnd Worker::Session::Lost() {
  if (!unexplained_.empty() && worker_.handshake_problem_.empty()) {
    options_.log(unexplained_);
    worker_.handshake_problem_ = unexplained_;
  }
  if (stopping_) return SessionEnd::kStopped;
  if (pool()) pool()->Abandon();  // The next master re-sends what it needs.
  return welcomed_ ? SessionEnd::kLostAfterWelcome : SessionEnd::kLost;
}

}  // namespace animat
