#include "common/protocol/handshake_monitor.h"

#include <atomic>
#include <cstring>

namespace animat::protocol {
namespace {

constexpr int kEvents =
    ZMQ_EVENT_HANDSHAKE_SUCCEEDED | ZMQ_EVENT_HANDSHAKE_FAILED_NO_DETAIL |
    ZMQ_EVENT_HANDSHAKE_FAILED_PROTOCOL | ZMQ_EVENT_HANDSHAKE_FAILED_AUTH;

HandshakeEvent Classify(uint16_t event, uint32_t value) {
  HandshakeEvent e;
  e.code = value;
  switch (event) {
    case ZMQ_EVENT_HANDSHAKE_SUCCEEDED:
      e.kind = HandshakeEvent::Kind::kSucceeded;
      break;
    case ZMQ_EVENT_HANDSHAKE_FAILED_AUTH:
      e.kind = HandshakeEvent::Kind::kRefusedKey;
      break;
    case ZMQ_EVENT_HANDSHAKE_FAILED_PROTOCOL:
      if (value == ZMQ_PROTOCOL_ERROR_ZMTP_MECHANISM_MISMATCH) {
        e.kind = HandshakeEvent::Kind::kMechanismMismatch;
      } else if (value == ZMQ_PROTOCOL_ERROR_ZMTP_CRYPTOGRAPHIC) {
        e.kind = HandshakeEvent::Kind::kCryptographic;
      }
      break;
    default:
      e.code = 0;  // No detail.
      break;
  }
  return e;
}

}  // namespace

HandshakeMonitor::HandshakeMonitor(zmq::context_t& context,
                                   zmq::socket_t& watched)
    : watched_(watched) {
  static std::atomic<uint64_t> count{0};
  const std::string address =
      "inproc://animat-handshake-monitor-" + std::to_string(++count);
  if (zmq_socket_monitor(watched.handle(), address.c_str(), kEvents) != 0) {
    return;
  }
  try {
    auto events =
        std::make_unique<zmq::socket_t>(context, zmq::socket_type::pair);
    events->set(zmq::sockopt::linger, 0);
    events->connect(address);
    events_ = std::move(events);
  } catch (const zmq::error_t&) {
    zmq_socket_monitor(watched.handle(), nullptr, 0);
  }
}

HandshakeMonitor::~HandshakeMonitor() {
  if (events_) zmq_socket_monitor(watched_.handle(), nullptr, 0);
}

std::vector<HandshakeEvent> HandshakeMonitor::Read() {
  std::vector<HandshakeEvent> events;
  if (!events_) return events;
  for (;;) {
    // Two frames an event: 6 bytes (event, value), then the endpoint.
    zmq::message_t head;
    zmq::message_t endpoint;
    try {
      if (!events_->recv(head, zmq::recv_flags::dontwait)) break;
      if (head.more()) (void)events_->recv(endpoint, zmq::recv_flags::none);
    } catch (const zmq::error_t&) {
      break;
    }
    if (head.size() < 6) continue;
    uint16_t event = 0;
    uint32_t value = 0;
    std::memcpy(&event, head.data(), sizeof(event));
    std::memcpy(&value, static_cast<const char*>(head.data()) + 2,
                sizeof(value));
    events.push_back(Classify(event, value));
  }
  return events;
}

}  // namespace animat::protocol
