#include "master/dispatch/zap_authenticator.h"

#include <chrono>
#include <vector>
#include <zmq.hpp>

#include "common/base/text.h"
#include "common/protocol/zmq_poll.h"
#include "common/security/curve_keys.h"

namespace animat {
namespace {

constexpr char kZapEndpoint[] = "inproc://zeromq.zap.01";
constexpr int kPollMs = 100;

void Reply(zmq::socket_t& socket, const std::string& request_id,
           const char* code, const std::string& text,
           const std::string& user_id) {
  const std::string frames[] = {"1.0", request_id, code, text, user_id, ""};
  for (size_t i = 0; i < 6; ++i) {
    socket.send(zmq::buffer(frames[i]),
                i + 1 < 6 ? zmq::send_flags::sndmore : zmq::send_flags::none);
  }
}

}  // namespace

Result<std::unique_ptr<ZapAuthenticator>> ZapAuthenticator::Start(
    zmq::context_t* context, std::map<std::string, std::string> allowed,
    LogSink log) {
  std::unique_ptr<ZapAuthenticator> zap(
      new ZapAuthenticator(std::move(allowed), std::move(log)));
  auto socket =
      std::make_unique<zmq::socket_t>(*context, zmq::socket_type::rep);
  try {
    socket->set(zmq::sockopt::linger, 0);
    socket->bind(kZapEndpoint);
  } catch (const zmq::error_t& e) {
    return Status::Internal(std::string("ZAP handler: ") + e.what());
  }
  // The socket moves to the thread; starting a thread is a full barrier.
  zap->thread_ = std::thread([raw = zap.get(), s = socket.release()]() mutable {
    std::unique_ptr<zmq::socket_t> owned(s);
    raw->Serve(owned.get());
  });
  return zap;
}

ZapAuthenticator::~ZapAuthenticator() {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
}

void ZapAuthenticator::Serve(void* raw_socket) {
  zmq::socket_t& socket = *static_cast<zmq::socket_t*>(raw_socket);
  while (!stop_.load()) {
    zmq::pollitem_t item{socket.handle(), 0, ZMQ_POLLIN, 0};
    if (protocol::Poll(&item, 1, std::chrono::milliseconds(kPollMs)) == 0 ||
        !(item.revents & ZMQ_POLLIN)) {
      continue;
    }
    std::vector<std::string> frames;
    for (;;) {
      zmq::message_t frame;
      if (!socket.recv(frame, zmq::recv_flags::none)) break;
      frames.push_back(frame.to_string());
      if (!frame.more() || frames.size() > 16) break;
    }
    // 1.0, request id, domain, address, routing id, mechanism, credentials.
    const std::string request_id = frames.size() > 1 ? frames[1] : "";
    if (frames.size() < 6 || frames[0] != "1.0") {
      Refused("malformed", "ZAP: malformed request refused");
      Reply(socket, request_id, "500", "malformed ZAP request", "");
      continue;
    }
    // Escaped: the mechanism's name comes from the peer.
    const std::string address = ForeignText(frames[3], 64);
    const std::string mechanism = ForeignText(frames[5], 20);
    if (mechanism != "CURVE" || frames.size() != 7 ||
        frames[6].size() != security::kKeyBytes) {
      Refused(address + " " + mechanism, "refused a worker from " + address +
                                             ": mechanism " + mechanism +
                                             ", not CurveZMQ");
      Reply(socket, request_id, "400", "CurveZMQ required", "");
      continue;
    }
    const std::string key = security::Z85Encode(frames[6]);
    const auto it = allowed_.find(key);
    if (it == allowed_.end()) {
      Refused(address + " " + key, "refused a worker from " + address +
                                       ": key " + key +
                                       " is not on the allow-list (logged "
                                       "once for this address and key)");
      Reply(socket, request_id, "400", "unknown key", "");
      continue;
    }
    ++admitted_;
    Reply(socket, request_id, "200", "OK", it->second);
  }
}

void ZapAuthenticator::Refused(const std::string& peer,
                               const std::string& line) {
  ++refused_;
  if (logged_.count(peer) != 0) return;
  if (logged_.size() < kMaxPeersLogged) {
    logged_.insert(peer);
    log_(line);
  } else if (logged_.size() == kMaxPeersLogged) {
    logged_.insert("");  // Said once.
    log_("refused " + std::to_string(kMaxPeersLogged) +
         " different workers; further refusals are not logged");
  }
}

}  // namespace animat
