// protocol::CheckEndpoint: what --bind and --connect accept, and what a
// mistyped endpoint is told.
#include "common/protocol/endpoint.h"

#include <gtest/gtest.h>

#include <string>

namespace animat::protocol {
namespace {

constexpr EndpointUse kBind = EndpointUse::kBind;
constexpr EndpointUse kConnect = EndpointUse::kConnect;

TEST(EndpointTest, TcpAndIpcEndpointsAreAccepted) {
  for (const char* endpoint :
       {"tcp://127.0.0.1:5555", "tcp://localhost:1",
        "tcp://node-7.cluster:65535", "tcp://[::1]:5555", "tcp://[fe80::1]:80",
        "ipc:///tmp/a.ipc", "ipc://relative.ipc"}) {
    EXPECT_TRUE(CheckEndpoint(endpoint, kBind).ok()) << endpoint;
    EXPECT_TRUE(CheckEndpoint(endpoint, kConnect).ok()) << endpoint;
  }
}

TEST(EndpointTest, OnlyAMasterMayBindEveryInterfaceOrAnyPort) {
  for (const char* endpoint :
       {"tcp://*:5555", "tcp://127.0.0.1:*", "tcp://*:*"}) {
    EXPECT_TRUE(CheckEndpoint(endpoint, kBind).ok()) << endpoint;
    EXPECT_FALSE(CheckEndpoint(endpoint, kConnect).ok()) << endpoint;
  }
}

TEST(EndpointTest, AMistypedEndpointIsToldWhatIsWrongAndWhatWasExpected) {
  const struct {
    const char* endpoint;
    const char* problem;
  } cases[] = {
      {"127.0.0.1:5555", "neither tcp:// nor ipc://"},
      {"http://host:80", "neither tcp:// nor ipc://"},
      {"", "neither tcp:// nor ipc://"},
      {"tcp://127.0.0.1", "no port"},
      {"tcp://127.0.0.1:abc", "the port \"abc\" is not a number"},
      {"tcp://127.0.0.1:", "the port \"\" is not a number"},
      {"tcp://127.0.0.1:0", "the port 0 is not from 1 to 65535"},
      {"tcp://127.0.0.1:65536", "the port 65536 is not from 1 to 65535"},
      {"tcp://127.0.0.1:123456", "the port \"123456\" is not a number"},
      {"tcp://:5555", "no host"},
      {"tcp://", "no port"},
      {"tcp://[::1]", "no port"},
      {"tcp://[::1:5555", "a malformed [IPv6] address"},
      {"tcp://a b:5555", "the host \"a b\" is no name or address"},
      {"tcp://a\nb:5555", "the host \"a\\nb\" is no name or address"},
      {"ipc://", "no path"},
  };
  for (const auto& c : cases) {
    const Status status = CheckEndpoint(c.endpoint, kConnect);
    ASSERT_FALSE(status.ok()) << c.endpoint;
    EXPECT_EQ(status.code(), StatusCode::kInvalidArgument);
    EXPECT_NE(status.message().find(c.problem), std::string::npos)
        << status.message();
    EXPECT_NE(status.message().find("expected tcp://HOST:PORT or ipc://PATH"),
              std::string::npos)
        << status.message();
  }
  EXPECT_NE(CheckEndpoint("5555", kBind)
                .message()
                .find("expected tcp://HOST:PORT (HOST or PORT may be *) or "
                      "ipc://PATH"),
            std::string::npos);
}

TEST(EndpointTest, AnIpcPathFitsAUnixSocketName) {
  EXPECT_TRUE(CheckEndpoint("ipc://" + std::string(107, 'a'), kBind).ok());
  const Status status = CheckEndpoint("ipc://" + std::string(108, 'a'), kBind);
  EXPECT_NE(status.message().find("longer than 107 bytes"), std::string::npos)
      << status.message();
}

TEST(EndpointTest, AHugeEndpointIsQuotedShort) {
  const Status status = CheckEndpoint(std::string(1 << 20, 'x'), kConnect);
  EXPECT_LT(status.message().size(), 400u);
}

}  // namespace
}  // namespace animat::protocol
