// The master's start-up (master/run/session.h), shared by animat-master and
// `animat evolve`: a port in use is found before the run is written, so a
// failed start leaves the store as it was; a resume never asks for fewer
// generations than the run has made; a stopped master prints the whole
// command that continues it, and that command, run as printed, does; a
// malformed endpoint is a usage error in both programs; workers told the
// run is finished leave with --exit-when-done.
#include <csignal>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <vector>
#include <zmq.hpp>

#include "tests/master/master_harness.h"

namespace animat::testing {
namespace {

// A TCP port on loopback held by a socket of the test, as another program
// would hold it.
class BusyPort {
 public:
  BusyPort() {
    socket_.bind("tcp://127.0.0.1:*");
    endpoint_ = socket_.get(zmq::sockopt::last_endpoint);
  }
  const std::string& endpoint() const { return endpoint_; }

 private:
  zmq::context_t context_{1};
  zmq::socket_t socket_{context_, zmq::socket_type::router};
  std::string endpoint_;
};

class StartupTest : public MasterTest {
 protected:
  // animat-master with `args` on `bind`, expected to exit 1 saying that it
  // cannot bind there.
  void ExpectCannotBind(const std::vector<std::string>& args,
                        const std::string& bind) {
    std::unique_ptr<ChildProcess> master = StartMaster(args, bind);
    ASSERT_TRUE(AwaitExit(*master, kStepWait, "a master on a busy port"));
    EXPECT_EQ(master->exit_code(), 1) << master->Describe();
    EXPECT_NE(master->standard_error().find("cannot bind " + bind),
              std::string::npos)
        << master->output();
  }

  // A store holding run 1 of `generations` generations, finished.
  std::string FinishedRun(int generations) {
    TestRun run;
    run.seed = 5;
    run.generations = generations;
    const std::string db = Path("finished.db");
    RunToEnd(WriteConfig("run.txtpb", run), db, /*workers=*/2);
    return db;
  }
};

TEST_F(StartupTest, ABusyPortLeavesAFreshStoreWithoutARun) {
  const BusyPort port;
  const std::string db = Path("fresh.db");
  ExpectCannotBind(
      {"--config", WriteConfig("run.txtpb", TestRun()), "--db", db},
      port.endpoint());
  const Progress progress = ReadProgress(db);
  EXPECT_FALSE(progress.has_run) << progress.ToString();
  // Nothing stuck: the same command on a free endpoint starts the run.
  std::unique_ptr<ChildProcess> master =
      StartRun(WriteConfig("run.txtpb", TestRun()), db);
  ASSERT_TRUE(AwaitOutput(*master, "run 1 started")) << master->output();
  ASSERT_TRUE(master->Signal(SIGTERM));
  ASSERT_TRUE(AwaitExit(*master, kStepWait, "SIGTERM"));
  EXPECT_EQ(master->exit_code(), 0) << master->output();
}

TEST_F(StartupTest, ABusyPortLeavesAResumedStoreAsItWas) {
  const std::string db = FinishedRun(2);
  if (HasFatalFailure()) return;
  const StoreContents before = ReadStoreContents(db);
  const std::vector<SqlRow> runs = QueryRows(db, "SELECT * FROM runs");
  const BusyPort port;
  // An extension would rewrite the run's generations and state.
  ExpectCannotBind({"--resume", "--db", db, "--generations", "4"},
                   port.endpoint());
  ExpectSameContents(before, ReadStoreContents(db));
  EXPECT_EQ(QueryRows(db, "SELECT * FROM runs"), runs);
}

TEST_F(StartupTest, ResumingWithFewerGenerationsThanMadeIsRefused) {
  const std::string db = FinishedRun(2);
  if (HasFatalFailure()) return;
  const StoreContents before = ReadStoreContents(db);
  std::unique_ptr<ChildProcess> master = Resume(db, {"--generations", "1"});
  ASSERT_TRUE(AwaitExit(*master, kStepWait, "a resume for fewer generations"));
  EXPECT_EQ(master->exit_code(), 1) << master->Describe();
  EXPECT_NE(master->standard_error().find(
                db +
                " holds run 1 (finished) with 2 generations; "
                "--generations 1 counts them all, so there is nothing "
                "to run. To extend it, ask for more than 2: " +
                std::string(ANIMAT_BIN_DIR) + "/animat-master --resume --db " +
                db + " --bind " + Endpoint() + " --heartbeat-ms " +
                std::to_string(kMasterHeartbeatMs) + " --generations 12"),
            std::string::npos)
      << master->output();
  ExpectSameContents(before, ReadStoreContents(db));
}

TEST_F(StartupTest, AFinishedRunIsNotServedAgain) {
  const std::string db = FinishedRun(2);
  if (HasFatalFailure()) return;
  const StoreContents before = ReadStoreContents(db);
  std::unique_ptr<ChildProcess> master = Resume(db);
  ASSERT_TRUE(AwaitExit(*master, kStepWait, "a resume of a finished run"));
  EXPECT_EQ(master->exit_code(), 0) << master->output();
  EXPECT_NE(master->output().find(
                "run 1 is finished (2 generations); to extend it: " +
                std::string(ANIMAT_BIN_DIR) + "/animat-master --resume"),
            std::string::npos)
      << master->output();
  EXPECT_EQ(master->output().find("listening on"), std::string::npos)
      << master->output();
  ExpectSameContents(before, ReadStoreContents(db));
}

TEST_F(StartupTest, TheResumeHintIsTheWholeCommandAndWorksAsPrinted) {
  TestRun run;
  run.seed = 6;
  run.generations = 3;
  const std::string db = Path("hint.db");
  std::unique_ptr<ChildProcess> master =
      StartRun(WriteConfig("run.txtpb", run), db);
  const auto workers = StartWorkers(2);
  ASSERT_TRUE(AwaitStore(
      db, [](const Progress& p) { return p.evaluated > 0; }, *master));
  ASSERT_TRUE(master->Signal(SIGTERM));
  ASSERT_TRUE(AwaitExit(*master, kStepWait, "SIGTERM"));
  ASSERT_EQ(master->exit_code(), 0) << master->output();
  // The program as it was started, so that the command runs as printed.
  const std::string expected = std::string(ANIMAT_BIN_DIR) +
                               "/animat-master --resume --db " + db +
                               " --bind " + Endpoint() + " --heartbeat-ms " +
                               std::to_string(kMasterHeartbeatMs);
  const std::string output = master->standard_output();
  const size_t hint = output.find("stopped; resume with: ");
  ASSERT_NE(hint, std::string::npos) << output;
  std::istringstream line(
      output.substr(hint + 22, output.find('\n', hint) - hint - 22));
  std::vector<std::string> words;
  for (std::string word; line >> word;) words.push_back(word);
  std::string printed;
  for (const std::string& w : words)
    printed += (printed.empty() ? "" : " ") + w;
  ASSERT_EQ(printed, expected);

  // As printed (the temporary paths need no quoting): the same workers
  // come back to it, and the run ends.
  ChildProcess resumed("animat-master", words,
                       ChildProcess::Lifetime::kExitsByItself);
  ASSERT_TRUE(resumed.started());
  ASSERT_TRUE(AwaitExit(resumed, kRunWait, "the resumed run"));
  EXPECT_EQ(resumed.exit_code(), 0) << resumed.output();
  EXPECT_TRUE(ReadProgress(db).finished) << ReadProgress(db).ToString();
}

TEST_F(StartupTest, TheResumeHintKeepsTheKeysAndQuotesWhatNeedsIt) {
  std::unique_ptr<ChildProcess> keygen =
      StartAnimat({"keygen", "--cluster", Path("keys")});
  ASSERT_TRUE(AwaitExit(*keygen, kStepWait, "keygen"));
  ASSERT_EQ(keygen->exit_code(), 0) << keygen->output();
  const std::string db = Path("keys run.db");  // A space: quoted.
  std::unique_ptr<ChildProcess> master =
      StartMaster({"--config", WriteConfig("run.txtpb", TestRun()), "--db", db,
                   "--curve-secret", Path("keys/master.key"), "--curve-allow",
                   Path("keys/workers.allow")},
                  "tcp://127.0.0.1:*");
  ASSERT_TRUE(AwaitOutput(*master, "run 1 started")) << master->output();
  ASSERT_TRUE(master->Signal(SIGTERM));
  ASSERT_TRUE(AwaitExit(*master, kStepWait, "SIGTERM"));
  ASSERT_EQ(master->exit_code(), 0) << master->output();
  // The closing line is the master's standard output, all of it.
  EXPECT_EQ(master->standard_output(),
            "stopped; resume with: " + std::string(ANIMAT_BIN_DIR) +
                "/animat-master --resume --db '" + db +
                "' --bind 'tcp://127.0.0.1:*' --curve-secret " +
                Path("keys/master.key") + " --curve-allow " +
                Path("keys/workers.allow") + " --heartbeat-ms " +
                std::to_string(kMasterHeartbeatMs) + "\n")
      << master->output();
}

TEST_F(StartupTest, MalformedEndpointsAreUsageErrorsInBothPrograms) {
  const std::string config = WriteConfig("run.txtpb", TestRun());
  const std::string db = Path("never.db");
  for (const std::string endpoint :
       {"127.0.0.1:5613", "tcp://127.0.0.1:abc", "http://localhost:80",
        "tcp://127.0.0.1:70000", "ipc://"}) {
    ChildProcess master("animat-master",
                        {std::string(ANIMAT_BIN_DIR) + "/animat-master",
                         "--config", config, "--db", db, "--bind", endpoint},
                        ChildProcess::Lifetime::kExitsByItself);
    ChildProcess worker(
        "animat-worker",
        {std::string(ANIMAT_BIN_DIR) + "/animat-worker", "--connect", endpoint},
        ChildProcess::Lifetime::kExitsByItself);
    for (ChildProcess* process : {&master, &worker}) {
      ASSERT_TRUE(AwaitExit(*process, kStepWait, endpoint));
      EXPECT_EQ(process->exit_code(), 2) << process->Describe();
      const std::string error = process->standard_error();
      EXPECT_NE(error.find("\"" + endpoint + "\""), std::string::npos) << error;
      EXPECT_NE(error.find("expected tcp://HOST:PORT"), std::string::npos)
          << error;
      EXPECT_EQ(error.find("terminate"), std::string::npos) << error;
    }
    EXPECT_FALSE(std::filesystem::exists(db)) << endpoint;
  }
}

TEST_F(StartupTest, EveryFlagRefusesMalformedValuesWithAMessage) {
  const std::string config = WriteConfig("run.txtpb", TestRun());
  const std::string db = Path("flags.db");
  const std::string junk = Path("junk.txtpb");
  ASSERT_TRUE(WriteFile(junk, "not { a config").ok());
  const std::string missing = Path("missing/file");
  const std::string huge(5000, '7');
  const std::string master_bin = std::string(ANIMAT_BIN_DIR) + "/animat-master";
  const std::string worker_bin = std::string(ANIMAT_BIN_DIR) + "/animat-worker";
  // Each case: the program's arguments, every other one valid (so that
  // only the malformed value can stop it).
  const std::vector<std::string> master = {
      master_bin, "--config", config, "--db", db, "--bind", Endpoint()};
  const std::vector<std::string> worker = {worker_bin, "--connect", Endpoint()};
  std::vector<std::vector<std::string>> cases;
  const auto with = [&](std::vector<std::string> base,
                        const std::vector<std::string>& more) {
    // A later value of a flag already given replaces it (CLI11 keeps the
    // last): drop the base's.
    for (size_t i = 1; i + 1 < base.size(); i += 2) {
      if (base[i] == more[0])
        base.erase(base.begin() + i, base.begin() + i + 2);
    }
    base.insert(base.end(), more.begin(), more.end());
    cases.push_back(base);
  };
  for (const std::string& value : {std::string(), missing, junk, Path("")}) {
    with(master, {"--config", value});
  }
  for (const std::string& value : {std::string(), missing, Path("")}) {
    with(master, {"--db", value});
  }
  for (const std::string& value :
       {std::string("0"), std::string("-1"), std::string("abc"),
        std::string("1e9"), huge}) {
    with(master, {"--generations", value});
    with(master, {"--heartbeat-ms", value});
    with(worker, {"--threads", value});
    with(worker, {"--heartbeat-ms", value});
  }
  for (const std::string& value :
       {std::string("-1"), std::string("abc"), huge}) {
    with(worker, {"--idle-timeout", value});
  }
  with(master, {"--curve-secret", missing, "--curve-allow", missing});
  with(master, {"--curve-secret", junk, "--curve-allow", junk});
  with(master, {"--curve-secret", missing});
  with(master, {"--resume=yes"});
  with(master, {"--no-such-flag"});
  with(worker, {"--curve-server", missing, "--curve-secret", missing});
  with(worker, {"--curve-server", junk, "--curve-secret", junk});
  with(worker, {"--exit-when-done=maybe"});
  with(worker, {"--no-such-flag"});
  with(worker, {"--connect", huge});
  // What a master runs to evaluate one genome alone (worker/evaluate_one.h).
  for (const std::string& value : {std::string(), missing, junk, huge}) {
    cases.push_back({worker_bin, "--evaluate-one", value, "--result",
                     Path("result.binpb")});
  }
  cases.push_back({worker_bin, "--evaluate-one", junk});
  cases.push_back({worker_bin, "--evaluate-one", junk, "--result"});

  for (const std::vector<std::string>& argv : cases) {
    std::string line;
    for (const std::string& word : argv) {
      line += " " + (word.size() > 40 ? word.substr(0, 40) + "..." : word);
    }
    SCOPED_TRACE(line);
    ChildProcess process("flags", argv, ChildProcess::Lifetime::kExitsByItself);
    ASSERT_TRUE(AwaitExit(process, kStepWait, line));
    EXPECT_EQ(process.term_signal(), 0) << process.Describe();
    EXPECT_TRUE(process.exit_code() == 1 || process.exit_code() == 2)
        << process.Describe() << "\n"
        << process.output();
    const std::string error = process.standard_error();
    EXPECT_FALSE(error.empty());
    EXPECT_EQ(error.find("terminate"), std::string::npos) << error;
  }
}

TEST_F(StartupTest, WorkersThatExitWhenDoneLeaveWithTheFinishedRun) {
  TestRun run;
  run.seed = 7;
  run.generations = 2;
  const std::string db = Path("done.db");
  std::unique_ptr<ChildProcess> master =
      StartRun(WriteConfig("run.txtpb", run), db);
  std::vector<std::unique_ptr<WorkerProcess>> workers;
  for (int i = 0; i < 2; ++i) {
    WorkerArgs args;
    args.endpoint = Endpoint();
    args.heartbeat_ms = kMasterHeartbeatMs;
    args.exit_when_done = true;
    workers.push_back(std::make_unique<WorkerProcess>(args));
  }
  ASSERT_TRUE(AwaitExit(*master, kRunWait, "the run"));
  ASSERT_EQ(master->exit_code(), 0) << master->output();
  ASSERT_TRUE(ReadProgress(db).finished);
  for (auto& worker : workers) {
    ASSERT_TRUE(AwaitExit(*worker, kStepWait, "a worker after the run"));
    EXPECT_EQ(worker->exit_code(), 0) << worker->output();
    EXPECT_NE(worker->output().find("exiting (--exit-when-done)"),
              std::string::npos)
        << worker->output();
  }
}

}  // namespace
}  // namespace animat::testing
