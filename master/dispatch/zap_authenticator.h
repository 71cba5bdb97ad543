// The master's ZAP handler (ZeroMQ RFC 27): admits a CurveZMQ worker only
// when its public key is on the allow-list, and logs a refused peer with
// its key and address once (a worker retrying is not logged again), for
// at most kMaxPeersLogged peers; refused() counts them all
// (docs/security.md).
//
// libzmq asks the handler over inproc://zeromq.zap.01 of the socket's
// context during each handshake; the handler answers on a thread of its
// own. Start it before binding a CURVE server socket on that context, and
// destroy it after closing the socket, before the context. The counters
// are safe to read from any thread.
#ifndef ANIMAT_MASTER_DISPATCH_ZAP_AUTHENTICATOR_H_
#define ANIMAT_MASTER_DISPATCH_ZAP_AUTHENTICATOR_H_

#include <atomic>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <thread>

#include "common/base/log.h"
#include "common/base/status.h"

namespace zmq {
class context_t;
}  // namespace zmq

namespace animat {

class ZapAuthenticator {
 public:
  // `allowed`: Z85 public key -> name for the log. `context` must outlive
  // the authenticator. Fails if another handler already serves `context`.
  static Result<std::unique_ptr<ZapAuthenticator>> Start(
      zmq::context_t* context, std::map<std::string, std::string> allowed,
      LogSink log);
  ~ZapAuthenticator();  // Stops the thread.

  int64_t admitted() const { return admitted_.load(); }
  int64_t refused() const { return refused_.load(); }

  // Distinct refused peers (address and key) logged one by one; beyond,
  // one line says so and the rest are only counted.
  static constexpr size_t kMaxPeersLogged = 100;

 private:
  ZapAuthenticator(std::map<std::string, std::string> allowed, LogSink log)
      : allowed_(std::move(allowed)), log_(std::move(log)) {}
  void Serve(void* socket);
  // Counts a refusal of `peer` and logs `line` if that peer is new.
  void Refused(const std::string& peer, const std::string& line);

  const std::map<std::string, std::string> allowed_;
  const LogSink log_;
  std::atomic<bool> stop_{false};
  std::atomic<int64_t> admitted_{0};
  std::atomic<int64_t> refused_{0};
  std::set<std::string> logged_;  // Peers logged; the handler thread's.
  std::thread thread_;
};

}  // namespace animat

#endif  // ANIMAT_MASTER_DISPATCH_ZAP_AUTHENTICATOR_H_
