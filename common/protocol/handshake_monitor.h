// How ZeroMQ handshakes on one socket end (zmq_socket_monitor): the only
// way either side learns that a CurveZMQ handshake failed, since a refused
// peer never gets as far as a message (docs/security.md, "What each side
// logs").
//
// Made right after its socket, before the socket binds or connects, on the
// socket's thread and context; read from the same thread whenever a poll
// finds handle() readable. The watched socket must outlive the monitor.
// Never throws: a monitor that cannot be set up has a null handle() and
// reads nothing. Not thread-safe.
#ifndef ANIMAT_COMMON_PROTOCOL_HANDSHAKE_MONITOR_H_
#define ANIMAT_COMMON_PROTOCOL_HANDSHAKE_MONITOR_H_

#include <cstdint>
#include <memory>
#include <string>
#include <vector>
#include <zmq.hpp>

namespace animat::protocol {

struct HandshakeEvent {
  enum class Kind {
    kSucceeded,
    // One side speaks CurveZMQ and the other does not.
    kMechanismMismatch,
    // The CurveZMQ boxes did not open: the client holds another server
    // public key than the server's (seen by the server).
    kCryptographic,
    // The server's ZAP handler refused the client's key (`code`: the ZAP
    // status, 400).
    kRefusedKey,
    // Any other failure (`code`: ZeroMQ's protocol error, or 0 when it
    // gives none, as a client whose server key is wrong sees it).
    kFailed,
  };
  Kind kind = Kind::kFailed;
  uint32_t code = 0;
};

class HandshakeMonitor {
 public:
  HandshakeMonitor(zmq::context_t& context, zmq::socket_t& watched);
  ~HandshakeMonitor();
  HandshakeMonitor(const HandshakeMonitor&) = delete;
  HandshakeMonitor& operator=(const HandshakeMonitor&) = delete;

  // For zmq_poll (ZMQ_POLLIN); null when the monitor could not be set up.
  void* handle() const { return events_ ? events_->handle() : nullptr; }
  // The handshakes ended since the last call, oldest first (never blocks).
  std::vector<HandshakeEvent> Read();

 private:
  zmq::socket_t& watched_;
  std::unique_ptr<zmq::socket_t> events_;
};

}  // namespace animat::protocol

#endif  // ANIMAT_COMMON_PROTOCOL_HANDSHAKE_MONITOR_H_
