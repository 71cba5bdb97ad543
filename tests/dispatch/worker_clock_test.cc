// A worker keeps its heartbeats and the master's liveness by the clock it
// is given (WorkerOptions::clock), not by the time that passes: on a
// ManualClock it stays silent and patient however long it waits in real
// time, and acts as soon as the clock is moved.
#include <gtest/gtest.h>

#include <chrono>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <vector>
#include <zmq.hpp>

#include "common/base/clock.h"
#include "common/protocol/protocol.h"
#include "tests/dispatch/fake_peers.h"
#include "worker/worker.h"

namespace animat::testing {
namespace {

using std::chrono::milliseconds;

constexpr int kHeartbeatMs = 50;
constexpr milliseconds kLongWait(10000);  // Only a failing test waits it.

bool IsHello(const v1::Envelope& e) { return e.has_hello(); }
bool IsHeartbeat(const v1::Envelope& e) { return e.has_heartbeat(); }

TEST(WorkerClockTest, HeartbeatsAndTheMastersSilenceFollowTheWorkersClock) {
  zmq::context_t context(1);
  FakeMaster master(context);  // Says nothing: a silent master.
  ManualClock clock;
  std::mutex mutex;
  std::string log;
  WorkerOptions options;
  options.endpoint = master.endpoint();
  options.heartbeat_ms = kHeartbeatMs;
  options.reconnect_min_ms = 10;
  options.reconnect_max_ms = 10;
  options.clock = &clock;
  options.log = [&](std::string_view line) {
    std::lock_guard<std::mutex> lock(mutex);
    log.append(line).append("\n");
  };
  Worker worker(options);
  std::thread thread([&] { worker.Run(); });

  ASSERT_TRUE(master.ReceiveEnvelope("", kLongWait, IsHello).has_value());
  // Eight heartbeat intervals of real time, none of the worker's: it sends
  // nothing and does not give up on the master.
  std::vector<v1::Envelope> seen;
  master.ReceiveEnvelope(
      "", milliseconds(8 * kHeartbeatMs),
      [](const v1::Envelope&) { return false; }, &seen);
  EXPECT_TRUE(seen.empty()) << seen.size() << " messages, the first "
                            << seen.front().ShortDebugString();
  // One interval on its clock: a heartbeat.
  clock.Advance(milliseconds(kHeartbeatMs));
  EXPECT_TRUE(master.ReceiveEnvelope("", kLongWait, IsHeartbeat).has_value());
  {
    std::lock_guard<std::mutex> lock(mutex);
    EXPECT_EQ(log.find("master silent"), std::string::npos) << log;
  }
  // Past kLiveness intervals without a word from the master: the worker
  // gives up on this session and says hello again.
  clock.Advance(milliseconds(protocol::kLiveness * kHeartbeatMs));
  EXPECT_TRUE(master.ReceiveEnvelope("", kLongWait, IsHello).has_value());
  {
    std::lock_guard<std::mutex> lock(mutex);
    EXPECT_NE(log.find("master silent"), std::string::npos) << log;
  }
  worker.Stop();
  thread.join();
}

}  // namespace
}  // namespace animat::testing
