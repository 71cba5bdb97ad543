// The master's log of the handshakes that fail on its socket: peers a
// CurveZMQ master refuses before any message (a worker without keys, or
// with another master's public key) and peers that ask a plain master for
// CurveZMQ (docs/security.md, "What each side logs"). Refused keys are
// the ZAP handler's to log, with the key and the address
// (zap_authenticator.h), and a handshake cut short without detail (a peer
// gone, a port scan) is not worth a line; ZeroMQ names no peer for the
// others, so each kind is logged once, then at most once a minute (of the
// clock) with how many more there were.
//
// Not thread-safe: the dispatcher's thread makes it, right after its
// socket and before binding, and reads it when handle() is readable.
#ifndef ANIMAT_MASTER_DISPATCH_HANDSHAKE_LOG_H_
#define ANIMAT_MASTER_DISPATCH_HANDSHAKE_LOG_H_

#include <cstdint>
#include <map>
#include <string>
#include <zmq.hpp>

#include "common/base/clock.h"
#include "common/base/log.h"
#include "common/protocol/handshake_monitor.h"

namespace animat {

class HandshakeLog {
 public:
  // `curve`: the socket is a CurveZMQ server. `watched` and `clock` must
  // outlive the log.
  HandshakeLog(zmq::context_t& context, zmq::socket_t& watched, bool curve,
               LogSink log, const Clock& clock);

  // The endpoint bound, for the lines.
  void set_endpoint(std::string endpoint) { endpoint_ = std::move(endpoint); }
  void* handle() const { return monitor_.handle(); }
  // Reads what has happened and logs it.
  void Read();

 private:
  struct Tally {
    bool logged = false;
    Clock::TimePoint last;  // When last logged.
    int64_t unreported = 0;
  };
  std::string Line(const protocol::HandshakeEvent& event) const;

  protocol::HandshakeMonitor monitor_;
  const bool curve_;
  const LogSink log_;
  const Clock& clock_;
  std::string endpoint_;
  std::map<protocol::HandshakeEvent::Kind, Tally> tallies_;
};

}  // namespace animat

#endif  // ANIMAT_MASTER_DISPATCH_HANDSHAKE_LOG_H_
