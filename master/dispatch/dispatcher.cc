#include "master/dispatch/dispatcher.h"

#include <algorithm>
#include <cmath>
#include <zmq.hpp>

#include "common/base/text.h"
#include "common/protocol/zmq_poll.h"
#include "common/security/curve_keys.h"
#include "master/dispatch/handshake_log.h"
#include "master/dispatch/zap_authenticator.h"

namespace animat {
namespace {

SchedulerOptions SchedulerFor(const DispatcherOptions& o) {
  SchedulerOptions s;
  s.heartbeat_ms = o.heartbeat_ms;
  s.lease_ms = o.lease_ms;
  s.isolation = o.isolation;
  s.accept_null_workers = o.accept_null_workers;
  s.acknowledge_on_receipt = o.acknowledge_on_receipt;
  s.log = o.log;
  s.idle_notice_ms = o.idle_notice_ms;
  s.notices = o.notices;
  s.clock = o.clock;
  return s;
}

}  // namespace

Status Dispatcher::CheckOptions(const DispatcherOptions& options) {
  if (options.heartbeat_ms < protocol::kMinHeartbeatMs ||
      options.heartbeat_ms > protocol::kMaxHeartbeatMs) {
    return Status::InvalidArgument(
        "heartbeat of " + std::to_string(options.heartbeat_ms) +
        " ms outside [" + std::to_string(protocol::kMinHeartbeatMs) + ", " +
        std::to_string(protocol::kMaxHeartbeatMs) + "]");
  }
  if (options.lease_ms < 1) {
    return Status::InvalidArgument("lease of " +
                                   std::to_string(options.lease_ms) + " ms");
  }
  const bool curve = !options.curve_secret_key.empty();
  if (!curve && !options.insecure &&
      !security::IsLocalEndpoint(options.endpoint)) {
    return Status::InvalidArgument(
        "listening on " + options.endpoint +
        " reaches beyond this machine: give the master CurveZMQ keys "
        "(--curve-secret and --curve-allow, made by animat keygen; "
        "docs/security.md) or, on a trusted network only, --insecure");
  }
  if (curve && (!security::IsZ85Key(options.curve_secret_key) ||
                options.curve_allowed.empty())) {
    return Status::InvalidArgument(
        "CurveZMQ needs a 40-character Z85 secret key and at least one "
        "allowed worker key");
  }
  return Status::Ok();
}

Result<std::unique_ptr<Dispatcher>> Dispatcher::Create(
    zmq::context_t* context, DispatcherOptions options, v1::Config model) {
  Status status = CheckOptions(options);
  if (!status.ok()) return status;
  const bool curve = !options.curve_secret_key.empty();
  const bool local = security::IsLocalEndpoint(options.endpoint);
  std::unique_ptr<Dispatcher> dispatcher(
      new Dispatcher(context, std::move(options), std::move(model)));
  DispatcherOptions& o = dispatcher->options_;
  if (curve) {
    // The handler must serve the context before the socket binds.
    Result<std::unique_ptr<ZapAuthenticator>> zap =
        ZapAuthenticator::Start(context, o.curve_allowed, o.log);
    if (!zap.ok()) return zap.status();
    dispatcher->zap_ = std::move(zap).value();
    dispatcher->socket_->set(zmq::sockopt::curve_server, 1);
    dispatcher->socket_->set(zmq::sockopt::curve_secretkey, o.curve_secret_key);
    dispatcher->socket_->set(zmq::sockopt::zap_domain, "animat");
  } else if (!local) {
    o.log("WARNING: listening on " + o.endpoint +
          " without CurveZMQ (--insecure): anyone who reaches it can read "
          "the genomes and send results");
  }
  try {
    dispatcher->socket_->bind(dispatcher->options_.endpoint);
    dispatcher->endpoint_ =
        dispatcher->socket_->get(zmq::sockopt::last_endpoint);
    dispatcher->handshakes_->set_endpoint(dispatcher->endpoint_);
  } catch (const zmq::error_t& e) {
    return Status::IoError("cannot bind " + dispatcher->options_.endpoint +
                           ": " + e.what());
  }
  dispatcher->scheduler_.set_endpoint(dispatcher->endpoint_);
  dispatcher->options_.log("listening on " + dispatcher->endpoint_ +
                           " (build " + protocol::BuildId() + ")" +
                           (curve ? ", CurveZMQ with " +
                                        std::to_string(o.curve_allowed.size()) +
                                        " allowed worker keys"
                                  : ""));
  return dispatcher;
}

Dispatcher::Dispatcher(zmq::context_t* context, DispatcherOptions options,
                       v1::Config model)
    : options_(std::move(options)),
      socket_(
          std::make_unique<zmq::socket_t>(*context, zmq::socket_type::router)),
      scheduler_(SchedulerFor(options_), std::move(model), this) {
  socket_->set(zmq::sockopt::linger, 0);
  // The most a worker sends: ZeroMQ drops a connection that sends more.
  socket_->set(zmq::sockopt::maxmsgsize, protocol::kMaxWorkerMessageBytes);
  // Sending to a vanished worker fails at once instead of queueing.
  socket_->set(zmq::sockopt::router_mandatory, 1);
  handshakes_ = std::make_unique<HandshakeLog>(
      *context, *socket_, !options_.curve_secret_key.empty(), options_.log,
      *options_.clock);
}

Dispatcher::~Dispatcher() = default;

void Dispatcher::Submit(uint64_t individual, const v1::Genome& genome) {
  if (scheduler_.IsPending(individual)) return;
  Submit(individual, protocol::SerializeGenome(genome));
}

void Dispatcher::Submit(uint64_t individual,
                        const protocol::SerializedGenome& genome) {
  scheduler_.Submit(individual, genome);
}

std::vector<Completion> Dispatcher::Poll(int timeout_ms) {
  std::vector<Completion> done;
  const Clock::TimePoint end =
      options_.clock->Now() + std::chrono::milliseconds(timeout_ms);
  for (;;) {
    scheduler_.Dispatch();
    // Round the time left up, so the last fraction of a millisecond is
    // waited for, not spun through.
    const auto left = std::chrono::ceil<std::chrono::milliseconds>(
        end - options_.clock->Now());
    const long wait = std::clamp<long>(left.count(), 0,
                                       std::max(1, options_.heartbeat_ms / 4));
    zmq::pollitem_t items[] = {{static_cast<void*>(*socket_), 0, ZMQ_POLLIN, 0},
                               {handshakes_->handle(), 0, ZMQ_POLLIN, 0}};
    protocol::Poll(items, items[1].socket != nullptr ? 2 : 1,
                   std::chrono::milliseconds(wait));
    if (items[0].revents & ZMQ_POLLIN) Receive(&done);
    if (items[1].revents & ZMQ_POLLIN) handshakes_->Read();
    scheduler_.Housekeep(&done);
    if (!done.empty() || options_.clock->Now() >= end) break;
  }
  scheduler_.Dispatch();
  return done;
}

void Dispatcher::Receive(std::vector<Completion>* done) {
  for (int burst = 0; burst < 10000; ++burst) {
    std::vector<zmq::message_t> frames;
    zmq::message_t frame;
    if (!socket_->recv(frame, zmq::recv_flags::dontwait)) return;
    frames.push_back(std::move(frame));
    while (frames.back().more()) {
      zmq::message_t next;
      if (!socket_->recv(next, zmq::recv_flags::dontwait)) break;
      frames.push_back(std::move(next));
    }
    const std::string identity = frames[0].to_string();
    if (frames.size() != 2) {
      scheduler_.Ignore("a message of " + std::to_string(frames.size()) +
                        " frames (expected identity + 1)");
      continue;
    }
    Result<v1::Envelope> envelope =
        protocol::Decode(frames[1].to_string_view());
    if (!envelope.ok() &&
        RefuseMalformedHello(identity, frames[1].data(), frames[1].size(),
                             envelope.status().message())) {
      continue;
    }
    if (!envelope.ok()) {
      scheduler_.Ignore("a malformed message from " +
                        scheduler_.PeerName(identity) + ": " +
                        envelope.status().message());
      continue;
    }
    scheduler_.Handle(identity, *envelope, done);
  }
}

bool Dispatcher::RefuseMalformedHello(const std::string& identity,
                                      const void* data, size_t size,
                                      const std::string& why) {
  // Only a frame a Hello may fill is parsed again (a larger one costs a
  // log line, as before).
  if (size > protocol::MaxEnvelopeBytes(v1::Envelope::kHello)) return false;
  v1::Envelope envelope;
  if (!envelope.ParseFromArray(data, static_cast<int>(size)) ||
      !envelope.has_hello()) {
    return false;
  }
  scheduler_.RefuseMalformed(identity, envelope.hello(), why);
  return true;
}

void Dispatcher::Acknowledge(const std::vector<uint64_t>& individuals) {
  scheduler_.Acknowledge(individuals);
}

void Dispatcher::Farewell(const std::string& reason) {
  scheduler_.Farewell(reason);
  // Delivered at close rather than dropped (the socket lingers no longer
  // than this).
  socket_->set(zmq::sockopt::linger, 1000);
}

bool Dispatcher::Deliver(const std::string& identity, const std::string& bytes,
                         std::string* problem) {
  try {
    // dontwait: an empty result means the peer's queue is full.
    if (!socket_->send(zmq::buffer(identity),
                       zmq::send_flags::sndmore | zmq::send_flags::dontwait) ||
        !socket_->send(zmq::buffer(bytes), zmq::send_flags::dontwait)) {
      *problem = "its queue is full";
      return false;
    }
  } catch (const zmq::error_t& e) {
    *problem = e.what();
    return false;
  }
  return true;
}

}  // namespace animat
