// The master's ZAP handler (master/dispatch/zap_authenticator.h) with real
// CurveZMQ sockets over TCP loopback: a worker key on the allow-list gets
// through, an unknown key and a plain (unencrypted) peer do not, and both
// refusals are logged.
#include "master/dispatch/zap_authenticator.h"

#include <gtest/gtest.h>

#include <chrono>
#include <mutex>
#include <string>
#include <vector>
#include <zmq.hpp>

#include "common/security/curve_keys.h"

namespace animat {
namespace {

using security::CurveKeyPair;
using security::GenerateKeyPair;

struct Lines {
  std::mutex mutex;
  std::vector<std::string> lines;
  LogSink Sink() {
    return [this](std::string_view line) {
      std::lock_guard<std::mutex> lock(mutex);
      lines.emplace_back(line);
    };
  }
  bool Any(const std::string& part) {
    std::lock_guard<std::mutex> lock(mutex);
    for (const std::string& line : lines) {
      if (line.find(part) != std::string::npos) return true;
    }
    return false;
  }
};

class ZapTest : public ::testing::Test {
 protected:
  void SetUp() override {
    Result<CurveKeyPair> server = GenerateKeyPair();
    Result<CurveKeyPair> known = GenerateKeyPair();
    Result<CurveKeyPair> stranger = GenerateKeyPair();
    ASSERT_TRUE(server.ok() && known.ok() && stranger.ok());
    server_ = *server;
    known_ = *known;
    stranger_ = *stranger;
    Result<std::unique_ptr<ZapAuthenticator>> zap = ZapAuthenticator::Start(
        &context_, {{known_.public_key, "known worker"}}, log_.Sink());
    ASSERT_TRUE(zap.ok()) << zap.status().ToString();
    zap_ = std::move(zap).value();
    router_ =
        std::make_unique<zmq::socket_t>(context_, zmq::socket_type::router);
    router_->set(zmq::sockopt::linger, 0);
    router_->set(zmq::sockopt::curve_server, 1);
    router_->set(zmq::sockopt::curve_secretkey, server_.secret_key);
    router_->set(zmq::sockopt::zap_domain, "animat");
    router_->bind("tcp://127.0.0.1:*");
    endpoint_ = router_->get(zmq::sockopt::last_endpoint);
  }
  void TearDown() override {
    router_.reset();
    zap_.reset();
  }

  // Connects a DEALER (CurveZMQ with `client` unless null), sends "hello"
  // and reports whether the router received it within `wait`.
  bool Delivered(const CurveKeyPair* client,
                 std::chrono::milliseconds wait = std::chrono::seconds(5)) {
    zmq::socket_t dealer(context_, zmq::socket_type::dealer);
    dealer.set(zmq::sockopt::linger, 0);
    if (client != nullptr) {
      dealer.set(zmq::sockopt::curve_serverkey, server_.public_key);
      dealer.set(zmq::sockopt::curve_publickey, client->public_key);
      dealer.set(zmq::sockopt::curve_secretkey, client->secret_key);
    }
    dealer.connect(endpoint_);
    dealer.send(zmq::str_buffer("hello"), zmq::send_flags::dontwait);
    zmq::pollitem_t item{router_->handle(), 0, ZMQ_POLLIN, 0};
    if (zmq::poll(&item, 1, wait) == 0) return false;
    zmq::message_t identity, body;
    EXPECT_TRUE(router_->recv(identity));
    EXPECT_TRUE(router_->recv(body));
    return body.to_string() == "hello";
  }

  zmq::context_t context_;
  Lines log_;
  CurveKeyPair server_, known_, stranger_;
  std::unique_ptr<ZapAuthenticator> zap_;
  std::unique_ptr<zmq::socket_t> router_;
  std::string endpoint_;
};

TEST_F(ZapTest, KnownKeyIsServed) {
  EXPECT_TRUE(Delivered(&known_));
  EXPECT_EQ(zap_->admitted(), 1);
  EXPECT_EQ(zap_->refused(), 0);
}

TEST_F(ZapTest, UnknownKeyIsRefusedAndLogged) {
  EXPECT_FALSE(Delivered(&stranger_, std::chrono::milliseconds(1500)));
  EXPECT_GE(zap_->refused(), 1);
  EXPECT_EQ(zap_->admitted(), 0);
  EXPECT_TRUE(
      log_.Any("key " + stranger_.public_key + " is not on the allow-list"));
  EXPECT_TRUE(log_.Any("127.0.0.1"));
  // A known worker is still served afterwards.
  EXPECT_TRUE(Delivered(&known_));
}

TEST_F(ZapTest, PlainPeerGetsNothingThrough) {
  EXPECT_FALSE(Delivered(nullptr, std::chrono::milliseconds(1500)));
  EXPECT_EQ(zap_->admitted(), 0);
}

TEST(ZapStartTest, SecondHandlerOnOneContextIsAnError) {
  zmq::context_t context;
  Result<std::unique_ptr<ZapAuthenticator>> first =
      ZapAuthenticator::Start(&context, {{"x", "y"}}, [](std::string_view) {});
  ASSERT_TRUE(first.ok());
  Result<std::unique_ptr<ZapAuthenticator>> second =
      ZapAuthenticator::Start(&context, {{"x", "y"}}, [](std::string_view) {});
  ASSERT_FALSE(second.ok());
  EXPECT_NE(second.status().message().find("ZAP"), std::string::npos);
}

}  // namespace
}  // namespace animat
