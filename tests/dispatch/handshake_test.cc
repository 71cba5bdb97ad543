// CurveZMQ refusals are said on both sides (docs/security.md, "What each
// side logs"), with real sockets over TCP loopback and real animat-worker
// processes: a worker without keys, with a key not on the allow-list, with
// another master's public key, or with keys against a plain master. Each
// side says what went wrong once, however often the worker tries again;
// a worker with the right keys is served as usual.
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "common/security/curve_keys.h"
#include "tests/child_process.h"
#include "tests/dispatch/dispatch_harness.h"

namespace animat::testing {
namespace {

using security::CurveKeyPair;

// Occurrences of `part` in `text`.
int Occurrences(const std::string& text, const std::string& part) {
  int n = 0;
  for (size_t at = text.find(part); at != std::string::npos;
       at = text.find(part, at + part.size())) {
    ++n;
  }
  return n;
}

// The first line of `output` (a worker's log: a timestamp, then the
// message) whose message appears again, other than the notices each
// session gives once (reconnecting, a heartbeat not sent); "" if none.
std::string RepeatedLine(const std::string& output) {
  std::set<std::string> seen;
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);) {
    const size_t message = line.find(' ');
    if (message == std::string::npos ||
        line.find("master silent; reconnecting") != std::string::npos ||
        line.find("said once a session") != std::string::npos) {
      continue;
    }
    if (!seen.insert(line.substr(message)).second) return line;
  }
  return "";
}

class HandshakeTest : public DispatchTest {
 protected:
  void SetUp() override {
    dir_ = ::testing::TempDir() + "/handshake-" + std::to_string(getpid());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
    for (const char* name : {"master", "worker", "stranger", "impostor"}) {
      Result<CurveKeyPair> pair = security::GenerateKeyPair();
      ASSERT_TRUE(pair.ok()) << pair.status().ToString();
      ASSERT_TRUE(WriteKeyPair(dir_ + "/" + name, *pair, name).ok());
      keys_[name] = *pair;
    }
  }
  void TearDown() override {
    std::filesystem::remove_all(dir_);
    DispatchTest::TearDown();
  }

  // A dispatcher on loopback, with CurveZMQ serving the "worker" key when
  // `curve`.
  bool StartMaster(bool curve) {
    DispatcherOptions options = Options();
    if (curve) {
      options.curve_secret_key = keys_["master"].secret_key;
      options.curve_allowed = {{keys_["worker"].public_key, "worker"}};
    }
    return StartDispatcher(options);
  }

  // An animat-worker for the dispatcher with the public key file of
  // `server` and the key pair of `client` ("": no keys).
  std::unique_ptr<ChildProcess> StartWorker(const std::string& server,
                                            const std::string& client) {
    std::vector<std::string> argv = {
        std::string(ANIMAT_BIN_DIR) + "/animat-worker",
        "--connect",
        dispatcher_->endpoint(),
        "--threads",
        "1",
        "--heartbeat-ms",
        "100"};
    if (!client.empty()) {
      argv.insert(argv.end(), {"--curve-server", dir_ + "/" + server + ".pub",
                               "--curve-secret", dir_ + "/" + client + ".key"});
    }
    auto worker = std::make_unique<ChildProcess>(
        "animat-worker", std::move(argv), ChildProcess::Lifetime::kStaysUp);
    EXPECT_TRUE(worker->started());
    return worker;
  }

  // Serves until the worker has said `worker_says` and has tried again
  // twice since (three sessions refused), and the master has logged
  // something with `master_says`; then expects the master to have said it
  // exactly once, and the worker to have said nothing twice (under load
  // ZeroMQ may first give the worker a failure without detail, said
  // before the precise reason).
  void ExpectEachSideSaysItOnce(ChildProcess& worker,
                                const std::string& worker_says,
                                const std::vector<std::string>& master_says) {
    const std::string again = "master silent; reconnecting";
    ASSERT_TRUE(Serve(
        [&] {
          const std::string out = worker.output();
          return Occurrences(out, again) >= 3 &&
                 Occurrences(out, worker_says) >= 1 &&
                 log_.Count(master_says) >= 1;
        },
        kLongWait))
        << "worker:\n"
        << worker.output() << "master:\n"
        << log_.Dump();
    EXPECT_EQ(RepeatedLine(worker.output()), "") << worker.output();
    EXPECT_EQ(log_.Count(master_says), 1) << log_.Dump();
    EXPECT_EQ(dispatcher_->workers(), 0u);
    EXPECT_TRUE(worker.Running());
    ASSERT_TRUE(worker.Signal(SIGTERM));
    EXPECT_TRUE(worker.WaitExit(kShortWait));
  }

  std::string dir_;
  std::map<std::string, CurveKeyPair> keys_;
};

TEST_F(HandshakeTest, WorkerWithoutKeysIsToldAndLoggedByTheMaster) {
  ASSERT_TRUE(StartMaster(/*curve=*/true));
  std::unique_ptr<ChildProcess> worker = StartWorker("", "");
  ExpectEachSideSaysItOnce(
      *worker,
      "requires CurveZMQ and refused this worker, which has no keys: give it "
      "--curve-server",
      {"refused a connection on " + dispatcher_->endpoint() +
       " without CurveZMQ"});
}

TEST_F(HandshakeTest, KeyNotOnTheAllowListIsNamedOnBothSides) {
  ASSERT_TRUE(StartMaster(/*curve=*/true));
  std::unique_ptr<ChildProcess> worker = StartWorker("master", "stranger");
  const std::string key = keys_["stranger"].public_key;
  ExpectEachSideSaysItOnce(
      *worker,
      "refused this worker's key " + key +
          " (CurveZMQ authentication, status 400): it must be on the "
          "master's allow-list",
      {"refused a worker from 127.0.0.1: key " + key +
       " is not on the allow-list"});
}

TEST_F(HandshakeTest, AnotherMastersPublicKeyIsSaidOnBothSides) {
  ASSERT_TRUE(StartMaster(/*curve=*/true));
  std::unique_ptr<ChildProcess> worker = StartWorker("impostor", "worker");
  ExpectEachSideSaysItOnce(
      *worker, "is --curve-server the master's public key?",
      {"whose CurveZMQ handshake failed: the worker's --curve-server is not "
       "this master's public key"});
}

TEST_F(HandshakeTest, WorkerWithKeysAgainstAPlainMasterIsToldWhy) {
  ASSERT_TRUE(StartMaster(/*curve=*/false));
  std::unique_ptr<ChildProcess> worker = StartWorker("master", "worker");
  ExpectEachSideSaysItOnce(
      *worker, "does not use CurveZMQ",
      {"that asked for CurveZMQ: this master has no keys"});
}

TEST_F(HandshakeTest, WorkerWithTheRightKeysIsServedAndNothingIsSaid) {
  ASSERT_TRUE(StartMaster(/*curve=*/true));
  const std::vector<Individual> population = Population(MixedGenomes(6), 1);
  Submit(population);
  std::unique_ptr<ChildProcess> worker = StartWorker("master", "worker");
  ASSERT_TRUE(ServeUntilAllDone()) << worker->output() << log_.Dump();
  ExpectEachCompletedOnceAsEvaluatedDirectly(population);
  EXPECT_EQ(log_.Count({"refused"}), 0) << log_.Dump();
  EXPECT_EQ(Occurrences(worker->output(), "refused"), 0) << worker->output();
  ASSERT_TRUE(worker->Signal(SIGTERM));
  ASSERT_TRUE(Serve([&] { return !worker->Running(); }, kShortWait));
  EXPECT_EQ(worker->exit_code(), 0);
}

}  // namespace
}  // namespace animat::testing
