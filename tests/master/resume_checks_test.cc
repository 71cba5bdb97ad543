// A resume continues the stored run only with the stored configuration and
// simulator build: another configuration or build is refused with a
// message saying which, unless --force, which then records the new
// configuration, keeping the old ones in the run's configuration history
// (`animat lineage configs`).
#include <csignal>
#include <filesystem>
#include <memory>
#include <string>

#include <sqlite3.h>

#include "animat/v1/evolution.pb.h"
#include "common/io/proto_file.h"
#include "tests/master/master_harness.h"

namespace animat::testing {
namespace {

// Runs `sql` on the store at `path`, with no master on it.
void Edit(const std::string& path, const std::string& sql) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  char* error = nullptr;
  const int rc = sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &error);
  EXPECT_EQ(rc, SQLITE_OK) << (error != nullptr ? error : "");
  sqlite3_free(error);
  sqlite3_close(db);
}

// The stored configuration of the store's only run.
v1::RunConfig StoredConfig(const std::string& db) {
  v1::RunConfig config;
  Result<std::vector<SqlRow>> rows =
      QueryStore(db, "SELECT hex(config) FROM runs");
  EXPECT_TRUE(rows.ok() && rows->size() == 1);
  if (!rows.ok() || rows->size() != 1) return config;
  const std::string& hex = (*rows)[0][0];
  std::string bytes;
  for (size_t i = 0; i + 1 < hex.size(); i += 2) {
    bytes += static_cast<char>(std::stoi(hex.substr(i, 2), nullptr, 16));
  }
  EXPECT_TRUE(config.ParseFromString(bytes));
  return config;
}

class ResumeChecksTest : public MasterTest {
 protected:
  // A store holding a stopped run of `config_`.
  void SetUp() override {
    MasterTest::SetUp();
    run_.seed = 21;
    config_ = WriteConfig("run.txtpb", run_);
    TestRun other = run_;
    other.seed = 22;
    other_config_ = WriteConfig("other.txtpb", other);
    db_ = Path("run.db");
    std::unique_ptr<ChildProcess> master = StartRun(config_, db_);
    ASSERT_TRUE(AwaitStore(
        db_, [](const Progress& p) { return p.individuals > 0; }, *master));
    ASSERT_TRUE(master->Signal(SIGTERM));
    ASSERT_TRUE(AwaitExit(*master, kStepWait, "SIGTERM"));
    ASSERT_EQ(master->exit_code(), 0) << master->output();
  }

  // A resume with `more`, expected to be refused for every one of
  // `reasons` (texts its message must hold), leaving the store as it was.
  void ExpectRefused(const std::vector<std::string>& more,
                     const std::vector<std::string>& reasons) {
    const StoreContents before = ReadStoreContents(db_);
    std::unique_ptr<ChildProcess> master = Resume(db_, more);
    ASSERT_TRUE(AwaitExit(*master, kStepWait, "a refused resume"));
    EXPECT_EQ(master->exit_code(), 1) << master->Describe();
    const std::string error = master->standard_error();
    for (const std::string& text :
         {db_ + ": refusing to resume", std::string("--force resumes")}) {
      EXPECT_NE(error.find(text), std::string::npos) << error;
    }
    for (const std::string& reason : reasons) {
      EXPECT_NE(error.find(reason), std::string::npos) << error;
    }
    ExpectSameContents(before, ReadStoreContents(db_));
  }

  // A resume with `more` that must start serving (then stopped by SIGTERM);
  // its output must hold each of `notes`.
  void ExpectAccepted(const std::vector<std::string>& more,
                      const std::vector<std::string>& notes) {
    std::unique_ptr<ChildProcess> master = Resume(db_, more);
    ASSERT_TRUE(AwaitOutput(*master, "resuming run 1"))
        << master->Describe() << "\n"
        << master->output();
    ASSERT_TRUE(master->Signal(SIGTERM));
    ASSERT_TRUE(AwaitExit(*master, kStepWait, "SIGTERM"));
    EXPECT_EQ(master->exit_code(), 0) << master->output();
    for (const std::string& note : notes) {
      EXPECT_NE(master->output().find(note), std::string::npos)
          << master->output();
    }
  }

  TestRun run_;
  std::string config_, other_config_, db_;
};

TEST_F(ResumeChecksTest, AnotherConfigurationIsRefusedUnlessForced) {
  ExpectRefused({"--config", other_config_},
                {"the configuration given differs from the run's"});
  EXPECT_EQ(StoredConfig(db_).evolution().seed(), 21u);

  // The same configuration, or another number of generations, is no
  // other run.
  ExpectAccepted({"--config", config_}, {});
  ExpectAccepted({"--config", config_, "--generations", "9"}, {});
  EXPECT_EQ(StoredConfig(db_).evolution().generations(), 9);

  ExpectAccepted({"--config", other_config_, "--force"},
                 {"resuming anyway (--force): the configuration given "
                  "differs"});
  const v1::RunConfig forced = StoredConfig(db_);
  EXPECT_EQ(forced.evolution().seed(), 22u);
  EXPECT_EQ(QueryInt(db_, "SELECT seed FROM runs"), 22);
  // Now the run's configuration: a plain resume takes it.
  ExpectAccepted({"--config", other_config_}, {});

  // Nothing of the provenance is lost: the history holds the configuration
  // the run started with, the extension, and the forced one, each from the
  // generation the run had reached, and the runs row the last.
  const std::vector<SqlRow> history = QueryRows(
      db_,
      "SELECT change, reason, config_hash = (SELECT config_hash FROM runs),"
      " from_generation FROM run_configs ORDER BY change");
  ASSERT_EQ(history.size(), 3u);
  EXPECT_EQ(history[0][1], "started");
  EXPECT_EQ(history[1][1], "generations set to 9");
  EXPECT_EQ(history[2][1],
            "--force: the configuration given differs from the run's");
  EXPECT_EQ(history[2][2], "1");
  EXPECT_EQ(history[0][2], "0");
  EXPECT_EQ(history[0][3], "0");
  EXPECT_LE(std::stoi(history[0][3]), std::stoi(history[1][3]));
  EXPECT_LE(std::stoi(history[1][3]), std::stoi(history[2][3]));
  EXPECT_EQ(QueryInt(db_,
                     "SELECT COUNT(DISTINCT config_hash) FROM "
                     "run_configs"),
            3);

  // animat lineage configs says the same, one line a configuration, and
  // writes the configuration in force at a generation.
  std::unique_ptr<ChildProcess> listed =
      StartAnimat({"lineage", "configs", "--db", db_});
  ASSERT_TRUE(AwaitExit(*listed, kStepWait, "lineage configs"));
  EXPECT_EQ(listed->exit_code(), 0) << listed->output();
  const std::string lines = listed->standard_output();
  EXPECT_NE(lines.find("0: from generation 0, config "), std::string::npos)
      << lines;
  EXPECT_NE(lines.find(": started\n1: from generation " + history[1][3]),
            std::string::npos)
      << lines;
  EXPECT_NE(lines.find(": --force: the configuration given differs from the "
                       "run's\n"),
            std::string::npos)
      << lines;
  const std::string latest = Path("latest.txtpb");
  std::unique_ptr<ChildProcess> written =
      StartAnimat({"lineage", "configs", "--db", db_, "--generation", "1000",
                   "-o", latest});
  ASSERT_TRUE(AwaitExit(*written, kStepWait, "lineage configs --generation"));
  EXPECT_EQ(written->exit_code(), 0) << written->output();
  v1::RunConfig in_force;
  ASSERT_TRUE(ReadProtoFile(latest, &in_force).ok());
  EXPECT_EQ(in_force.evolution().seed(), 22u);
}

TEST_F(ResumeChecksTest, AnotherSimulatorBuildIsRefusedUnlessForced) {
  Edit(db_, "UPDATE runs SET build_id = 'animat 0.0 other-build'");
  ExpectRefused({}, {"the run was evaluated by build \"animat 0.0 "
                     "other-build\""});
  ExpectRefused({"--config", other_config_},
                {"the configuration given differs", "other-build"});
  ExpectAccepted({"--force"},
                 {"resuming anyway (--force): the run was "
                  "evaluated by build \"animat 0.0 other-build\""});
  EXPECT_EQ(StoredConfig(db_).evolution().seed(), 21u);
  // The run goes on with this build: it is recorded, and the next resume
  // needs no --force.
  EXPECT_NE(QueryCell(db_, "SELECT build_id FROM runs"),
            "animat 0.0 other-build");
  ExpectAccepted({}, {});
}

TEST_F(MasterTest, AResumeNeedsAStoreThatHoldsARun) {
  // No store: refused, and none made.
  const std::string missing = Path("missing.db");
  std::unique_ptr<ChildProcess> master = Resume(missing);
  ASSERT_TRUE(AwaitExit(*master, kStepWait, "a resume of nothing"));
  EXPECT_EQ(master->exit_code(), 1);
  EXPECT_NE(master->standard_error().find(missing +
                                          ": no such lineage store to resume"),
            std::string::npos)
      << master->output();
  EXPECT_FALSE(std::filesystem::exists(missing));

  // A store without a run (an empty file becomes one).
  const std::string empty = Path("empty.db");
  ASSERT_TRUE(WriteFile(empty, "").ok());
  master = Resume(empty);
  ASSERT_TRUE(AwaitExit(*master, kStepWait, "a resume of an empty store"));
  EXPECT_EQ(master->exit_code(), 1);
  EXPECT_NE(master->standard_error().find(
                empty + ": no run to resume; start one with --config"),
            std::string::npos)
      << master->output();
}

}  // namespace
}  // namespace animat::testing
