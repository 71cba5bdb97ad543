#include "master/dispatch/handshake_log.h"

#include <chrono>
#include <utility>

namespace animat {
namespace {

constexpr std::chrono::seconds kReportEvery{60};

}  // namespace

HandshakeLog::HandshakeLog(zmq::context_t& context, zmq::socket_t& watched,
                           bool curve, LogSink log, const Clock& clock)
    : monitor_(context, watched),
      curve_(curve),
      log_(std::move(log)),
      clock_(clock) {}

std::string HandshakeLog::Line(const protocol::HandshakeEvent& event) const {
  using Kind = protocol::HandshakeEvent::Kind;
  const std::string on = " on " + endpoint_;
  switch (event.kind) {
    case Kind::kMechanismMismatch:
      return curve_ ? "refused a connection" + on +
                          " without CurveZMQ: a worker needs --curve-server "
                          "(this master's public key) and --curve-secret "
                          "(docs/security.md)"
                    : "refused a connection" + on +
                          " that asked for CurveZMQ: this master has no keys "
                          "(give it --curve-secret and --curve-allow, or start "
                          "the worker without keys)";
    case Kind::kCryptographic:
      return "refused a connection" + on +
             " whose CurveZMQ handshake failed: the worker's --curve-server "
             "is not this master's public key";
    default:
      return "a handshake failed" + on + " (ZeroMQ error " +
             std::to_string(event.code) + ")";
  }
}

void HandshakeLog::Read() {
  using Kind = protocol::HandshakeEvent::Kind;
  for (const protocol::HandshakeEvent& event : monitor_.Read()) {
    // Refused keys: the ZAP handler logs them with the key and address.
    // A failure without detail is a peer gone during its handshake (the
    // echo of its own refusal, or a port scan): nothing to say.
    if (event.kind == Kind::kSucceeded || event.kind == Kind::kRefusedKey ||
        (event.kind == Kind::kFailed && event.code == 0)) {
      continue;
    }
    Tally& tally = tallies_[event.kind];
    const Clock::TimePoint now = clock_.Now();
    if (tally.logged && now - tally.last < kReportEvery) {
      ++tally.unreported;
      continue;
    }
    std::string line = Line(event);
    if (tally.unreported > 0) {
      line += " (and " + std::to_string(tally.unreported) +
              " more since the last such line)";
    }
    log_(line);
    tally = {true, now, 0};
  }
}

}  // namespace animat
