// Peers played by the test on raw ZeroMQ sockets, for the cases a real
// worker or master never produces: garbage, wrong versions, silence, late
// answers, dying mid-work.
//
// FakeWorker is a DEALER connected to a master; FakeMaster a ROUTER bound
// on a free loopback port. Both send exactly what the test asks, record
// what arrives, and never block longer than asked. A FakeWorker keeps its
// heartbeats by a clock (a ManualClock in tests on simulated time);
// FakeMaster by real time. Not thread-safe; the sockets must be destroyed
// before their context.
#ifndef ANIMAT_TESTS_DISPATCH_FAKE_PEERS_H_
#define ANIMAT_TESTS_DISPATCH_FAKE_PEERS_H_

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>
#include <zmq.hpp>

#include "animat/v1/protocol.pb.h"
#include "common/base/clock.h"
#include "common/protocol/genome_wire.h"
#include "common/protocol/protocol.h"
#include "common/protocol/zmq_poll.h"

namespace animat::testing {

// A hello as a real worker of this build sends it (a made-up host, so the
// dispatcher's name for it is "fake-worker:<pid>").
// `instance`: Hello.instance (0: none, as before it existed).
inline v1::Envelope FakeHello(int threads, uint64_t pid,
                              uint64_t instance = 0) {
  v1::Envelope envelope;
  v1::Hello* hello = envelope.mutable_hello();
  hello->set_protocol_version(protocol::kVersion);
  hello->set_build_id(protocol::BuildId());
  hello->set_threads(static_cast<uint32_t>(threads));
  hello->set_host("fake-worker");
  hello->set_pid(pid);
  hello->set_instance(instance);
  return envelope;
}

// A welcome as a master of this build sends it: `config` and its hash, or
// `hash` in its place (a mismatch on purpose).
inline v1::Envelope FakeWelcome(const v1::Config& config, uint32_t heartbeat_ms,
                                std::optional<uint64_t> hash = std::nullopt) {
  v1::Envelope envelope;
  v1::Welcome* w = envelope.mutable_welcome();
  w->set_protocol_version(protocol::kVersion);
  w->set_build_id(protocol::BuildId());
  *w->mutable_config() = config;
  w->set_config_hash(hash.value_or(protocol::ConfigHash(config)));
  w->set_heartbeat_ms(heartbeat_ms);
  return envelope;
}

class FakeWorker {
 public:
  // `clock` must outlive the worker.
  FakeWorker(zmq::context_t& context, const std::string& endpoint,
             const animat::Clock& clock = animat::RealClock())
      : socket_(context, zmq::socket_type::dealer),
        clock_(clock),
        last_sent_(clock.Now()) {
    socket_.set(zmq::sockopt::linger, 0);
    socket_.connect(endpoint);
  }

  // Multi-frame when given several frames.
  void SendFrames(const std::vector<std::string>& frames) {
    for (size_t i = 0; i < frames.size(); ++i) {
      socket_.send(zmq::buffer(frames[i]), i + 1 < frames.size()
                                               ? zmq::send_flags::sndmore
                                               : zmq::send_flags::none);
    }
    last_sent_ = clock_.Now();
  }
  void SendRaw(const std::string& bytes) { SendFrames({bytes}); }
  // One frame of `size` bytes at `data`, not copied: `data` must outlive
  // the socket.
  void SendZeroCopy(const void* data, size_t size) {
    zmq::message_t message(
        const_cast<void*>(data), size, [](void*, void*) {}, nullptr);
    socket_.send(message, zmq::send_flags::none);
    last_sent_ = clock_.Now();
  }
  // Stamped with this build's protocol version.
  void Send(const v1::Envelope& envelope) {
    SendRaw(protocol::Encode(envelope));
  }

  // Says hello as "fake-worker:<pid>" with `threads` threads.
  void Hello(int threads, uint64_t pid, uint64_t instance = 0) {
    Send(FakeHello(threads, pid, instance));
  }
  void Credit(uint32_t credit) {
    v1::Envelope envelope;
    envelope.mutable_credit()->set_credit(credit);
    Send(envelope);
  }
  void Heartbeat() {
    v1::Envelope envelope;
    envelope.mutable_heartbeat();
    Send(envelope);
  }

  // From now on, Pump counts the times the connection is dropped (a
  // ZeroMQ socket monitor).
  void WatchDisconnects(zmq::context_t& context) {
    static int count = 0;
    const std::string address =
        "inproc://fake-worker-monitor-" + std::to_string(++count);
    zmq_socket_monitor(socket_.handle(), address.c_str(),
                       ZMQ_EVENT_DISCONNECTED);
    monitor_ = std::make_unique<zmq::socket_t>(context, zmq::socket_type::pair);
    monitor_->set(zmq::sockopt::linger, 0);
    monitor_->connect(address);
  }
  int disconnects() const { return disconnects_; }

  // Reads whatever has arrived, without waiting, and sends a heartbeat when
  // nothing was sent for 40 ms of its clock (unless `silent`).
  void Pump() {
    for (zmq::message_t event;
         monitor_ != nullptr &&
         monitor_->recv(event, zmq::recv_flags::dontwait);) {
      if (!event.more()) ++disconnects_;  // The second frame ends an event.
    }
    for (;;) {
      zmq::message_t frame;
      if (!socket_.recv(frame, zmq::recv_flags::dontwait)) break;
      Result<v1::Envelope> envelope = protocol::Decode(frame.to_string_view());
      if (!envelope.ok() || frame.more()) {
        ++undecodable_;
        continue;
      }
      if (envelope->has_work()) {
        for (const v1::WorkItem& item : envelope->work().items()) {
          work_items_.push_back(item);
        }
        work_messages_.push_back(envelope->work());
      }
      if (envelope->has_welcome()) welcomed_ = true;
      if (envelope->has_refuse()) refusal_ = envelope->refuse().reason();
      received_.push_back(std::move(envelope).value());
    }
    if (!silent_ && clock_.Now() - last_sent_ > std::chrono::milliseconds(40)) {
      Heartbeat();
    }
  }

  // Stops the automatic heartbeats of Pump.
  void set_silent(bool silent) { silent_ = silent; }

  // Waits up to `timeout` (real time) for something to read, then Pumps.
  void PumpWhenReady(std::chrono::milliseconds timeout) {
    zmq::pollitem_t item = {static_cast<void*>(socket_), 0, ZMQ_POLLIN, 0};
    protocol::Poll(&item, 1, timeout);
    Pump();
  }

  bool welcomed() const { return welcomed_; }
  const std::optional<std::string>& refusal() const { return refusal_; }
  const std::vector<v1::WorkItem>& work_items() const { return work_items_; }
  const std::vector<v1::Work>& work_messages() const { return work_messages_; }
  const std::vector<v1::Envelope>& received() const { return received_; }
  int undecodable() const { return undecodable_; }

 private:
  zmq::socket_t socket_;
  const animat::Clock& clock_;
  std::unique_ptr<zmq::socket_t> monitor_;
  int disconnects_ = 0;
  animat::Clock::TimePoint last_sent_;
  bool silent_ = false;
  bool welcomed_ = false;
  std::optional<std::string> refusal_;
  std::vector<v1::WorkItem> work_items_;
  std::vector<v1::Work> work_messages_;
  std::vector<v1::Envelope> received_;
  int undecodable_ = 0;
};

// One message a FakeMaster received: the sender's identity and the frames.
struct RoutedMessage {
  std::string identity;
  std::vector<std::string> frames;
};

class FakeMaster {
 public:
  explicit FakeMaster(zmq::context_t& context)
      : socket_(context, zmq::socket_type::router) {
    socket_.set(zmq::sockopt::linger, 0);
    socket_.bind("tcp://127.0.0.1:*");
    endpoint_ = socket_.get(zmq::sockopt::last_endpoint);
  }

  const std::string& endpoint() const { return endpoint_; }

  // The next message, waiting at most `timeout`.
  std::optional<RoutedMessage> Receive(std::chrono::milliseconds timeout) {
    zmq::pollitem_t item = {static_cast<void*>(socket_), 0, ZMQ_POLLIN, 0};
    protocol::Poll(&item, 1, timeout);
    zmq::message_t frame;
    if (!socket_.recv(frame, zmq::recv_flags::dontwait)) return std::nullopt;
    RoutedMessage message;
    message.identity = frame.to_string();
    while (frame.more()) {
      if (!socket_.recv(frame, zmq::recv_flags::dontwait)) break;
      message.frames.push_back(frame.to_string());
    }
    return message;
  }

  // Waits up to `timeout` for an envelope from `identity` (any peer when
  // empty) that `wanted` accepts, sending it a heartbeat every 40 ms; every
  // envelope decoded meanwhile is appended to `seen` (may be null).
  template <typename Predicate>
  std::optional<RoutedMessage> ReceiveEnvelope(
      const std::string& identity, std::chrono::milliseconds timeout,
      Predicate wanted, std::vector<v1::Envelope>* seen = nullptr) {
    using Steady = std::chrono::steady_clock;
    const auto end = Steady::now() + timeout;
    auto last_beat = Steady::now();
    while (Steady::now() < end) {
      if (!identity.empty() &&
          Steady::now() - last_beat > std::chrono::milliseconds(40)) {
        v1::Envelope beat;
        beat.mutable_heartbeat();
        Send(identity, beat);
        last_beat = Steady::now();
      }
      std::optional<RoutedMessage> message =
          Receive(std::chrono::milliseconds(20));
      if (!message || message->frames.size() != 1) continue;
      if (!identity.empty() && message->identity != identity) continue;
      Result<v1::Envelope> envelope = protocol::Decode(message->frames[0]);
      if (!envelope.ok()) continue;
      if (seen != nullptr) seen->push_back(*envelope);
      if (wanted(*envelope)) return message;
    }
    return std::nullopt;
  }

  void SendFrames(const std::string& identity,
                  const std::vector<std::string>& frames) {
    socket_.send(zmq::buffer(identity), zmq::send_flags::sndmore);
    for (size_t i = 0; i < frames.size(); ++i) {
      socket_.send(zmq::buffer(frames[i]), i + 1 < frames.size()
                                               ? zmq::send_flags::sndmore
                                               : zmq::send_flags::none);
    }
  }
  void Send(const std::string& identity, const v1::Envelope& envelope) {
    SendFrames(identity, {protocol::Encode(envelope)});
  }

 private:
  zmq::socket_t socket_;
  std::string endpoint_;
};

}  // namespace animat::testing

#endif  // ANIMAT_TESTS_DISPATCH_FAKE_PEERS_H_
