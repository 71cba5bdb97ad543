// The lineage store's schema, migrations, lock and read-only opening
// (master/lineage/schema.h, store.h).
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <sqlite3.h>

#include "master/lineage/schema.h"
#include "master/lineage/sqlite.h"
#include "master/lineage/store.h"
#include "tests/lineage/lineage_test_util.h"
#include "tests/lineage/store_test_peer.h"

namespace animat::lineage {
namespace {

using ::animat::testing::MakeIndividual;
using ::animat::testing::MakeRun;
using ::animat::testing::MemoryStore;
using ::animat::testing::Rows;
using ::animat::testing::TempStorePath;
using ::animat::testing::Value;

bool Contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// Writes an SQLite file at `path` whose user_version is `version` and
// which holds nothing else.
void MakeVersionedFile(const std::string& path, int version) {
  Result<std::unique_ptr<sql::Database>> db = sql::Database::Open(path);
  ASSERT_TRUE(db.ok()) << db.status().ToString();
  ASSERT_TRUE(
      (*db)->Execute("PRAGMA user_version = " + std::to_string(version)).ok());
}

int UserVersion(const std::string& path) {
  Result<std::unique_ptr<sql::Database>> db =
      sql::Database::Open(path, /*read_only=*/true);
  EXPECT_TRUE(db.ok()) << db.status().ToString();
  if (!db.ok()) return -1;
  Result<int> version = SchemaVersion(**db);
  EXPECT_TRUE(version.ok()) << version.status().ToString();
  return version.ok() ? *version : -1;
}

// What a child process reports: its exit code and the text it wrote.
struct ChildReport {
  int exit_code = -1;
  std::string text;
};

// Runs `body` in a forked child; the child writes the message of the
// Status it returns to a pipe and exits 0 for OK, 1 otherwise.
ChildReport RunInChild(const std::function<Status()>& body) {
  int fds[2];
  if (pipe(fds) != 0) {
    ADD_FAILURE() << "pipe failed";
    return {};
  }
  const pid_t pid = fork();
  if (pid == 0) {
    close(fds[0]);
    const Status status = body();
    const std::string& message = status.message();
    ssize_t written = write(fds[1], message.data(), message.size());
    (void)written;
    close(fds[1]);
    _exit(status.ok() ? 0 : 1);
  }
  close(fds[1]);
  ChildReport report;
  char buffer[512];
  for (;;) {
    const ssize_t n = read(fds[0], buffer, sizeof(buffer));
    if (n <= 0) break;
    report.text.append(buffer, static_cast<size_t>(n));
  }
  close(fds[0]);
  int wait_status = 0;
  if (pid < 0 || waitpid(pid, &wait_status, 0) != pid) {
    ADD_FAILURE() << "fork or waitpid failed";
    return report;
  }
  report.exit_code = WIFEXITED(wait_status) ? WEXITSTATUS(wait_status) : -1;
  return report;
}

Status OpenAndClose(const std::string& path) {
  Result<std::unique_ptr<Store>> store = Store::Open(path);
  return store.ok() ? Status::Ok() : store.status();
}

TEST(SchemaTest, NewStoreHasCurrentVersionTablesViewsAndIndexes) {
  std::unique_ptr<Store> store = MemoryStore();
  ASSERT_NE(store, nullptr);
  EXPECT_EQ(SchemaVersion(StoreTestPeer::Database(*store)).value(),
            kSchemaVersion);
  const std::vector<std::vector<std::string>> objects =
      Rows(*store,
           "SELECT type, name FROM sqlite_schema WHERE name NOT LIKE "
           "'sqlite_%' ORDER BY type, name");
  const std::vector<std::vector<std::string>> expected = {
      {"index", "births_by_generation"},
      {"index", "parents_by_parent"},
      {"table", "births"},
      {"table", "evaluations"},
      {"table", "generations"},
      {"table", "members"},
      {"table", "parents"},
      {"table", "run_configs"},
      {"table", "runs"},
      {"table", "trials"},
      {"view", "ancestry"},
      {"view", "best"},
      {"view", "generation_statistics"},
      {"view", "individuals"},
      {"view", "line_of_descent"},
  };
  EXPECT_EQ(objects, expected);
  // The views compile against the tables (an empty store answers them).
  for (const char* view : {"ancestry", "best", "generation_statistics",
                           "individuals", "line_of_descent"}) {
    EXPECT_EQ(Value(*store, std::string("SELECT COUNT(*) FROM ") + view), "0")
        << view;
  }
}

TEST(SchemaTest, FileStoreUsesWalNormalSyncForeignKeysAndLargeCache) {
  TempStorePath file("pragmas");
  Result<std::unique_ptr<Store>> store = Store::Open(file.path());
  ASSERT_TRUE(store.ok()) << store.status().ToString();
  EXPECT_EQ(Value(**store, "PRAGMA journal_mode"), "wal");
  EXPECT_EQ(Value(**store, "PRAGMA synchronous"), "1");  // NORMAL.
  EXPECT_EQ(Value(**store, "PRAGMA foreign_keys"), "1");
  EXPECT_EQ(Value(**store, "PRAGMA cache_size"), "-65536");  // KiB.
  EXPECT_EQ(Value(**store, "PRAGMA wal_autocheckpoint"), "16384");
}

TEST(SchemaTest, EmptyFileIsMigratedFromVersionZero) {
  TempStorePath file("empty");
  { std::ofstream touch(file.path()); }
  ASSERT_EQ(UserVersion(file.path()), 0);
  {
    Result<std::unique_ptr<Store>> store = Store::Open(file.path());
    ASSERT_TRUE(store.ok()) << store.status().ToString();
    EXPECT_EQ(Value(**store,
                    "SELECT COUNT(*) FROM sqlite_schema WHERE type = "
                    "'table' AND name = 'births'"),
              "1");
  }
  EXPECT_EQ(UserVersion(file.path()), kSchemaVersion);
}

TEST(SchemaTest, ReopeningKeepsDataAndDoesNotMigrateAgain) {
  TempStorePath file("reopen");
  {
    Result<std::unique_ptr<Store>> store = Store::Open(file.path());
    ASSERT_TRUE(store.ok()) << store.status().ToString();
    const int64_t run = MakeRun(**store);
    ASSERT_TRUE((*store)->AddIndividuals(run, {MakeIndividual(0, 0)}).ok());
  }
  Result<std::unique_ptr<Store>> store = Store::Open(file.path());
  ASSERT_TRUE(store.ok()) << store.status().ToString();
  EXPECT_EQ(SchemaVersion(StoreTestPeer::Database(**store)).value(),
            kSchemaVersion);
  EXPECT_EQ(Value(**store, "SELECT COUNT(*) FROM individuals"), "1");
}

// The columns of `individuals` up to schema version 3, in their order,
// each as text that keeps every bit (quote()).
constexpr const char* kVersion3Columns =
    "run_id, id, generation, operators, quote(genome), genome_hash,"
    " elements, created_at, status, reason, quote(fitness), cells, steps,"
    " quote(wall_seconds), worker, state_hash, evaluated_at";

// The columns schema version 4 added, after those.
const std::vector<std::string> kBodyColumns = {
    "springs", "chambers", "skin_edges", "spread_major", "spread_minor"};

// Every row of `query` on the file at `path`, opened read-only without
// the store's code (which would migrate it); each column as text, "NULL"
// for NULL.
std::vector<std::vector<std::string>> RawRows(const std::string& path,
                                              const std::string& query) {
  std::vector<std::vector<std::string>> rows;
  Result<std::unique_ptr<sql::Database>> db =
      sql::Database::Open(path, /*read_only=*/true);
  EXPECT_TRUE(db.ok()) << db.status().ToString();
  if (!db.ok()) return rows;
  const auto collect = [](void* out, int columns, char** values,
                          char**) -> int {
    std::vector<std::string> row;
    for (int c = 0; c < columns; ++c) {
      row.push_back(values[c] != nullptr ? values[c] : "NULL");
    }
    static_cast<std::vector<std::vector<std::string>>*>(out)->push_back(
        std::move(row));
    return 0;
  };
  char* error = nullptr;
  if (sqlite3_exec((*db)->handle(), query.c_str(), collect, &rows, &error) !=
      SQLITE_OK) {
    ADD_FAILURE() << query << ": " << (error != nullptr ? error : "error");
    sqlite3_free(error);
  }
  return rows;
}

// A store written by schema version 1 (individuals WITHOUT ROWID) or 2
// (evaluations in the individuals table) is upgraded in place: every row
// and column survives, read through the individuals view, and the body
// columns are NULL; the views answer; births is a rowid table with the
// generation index and evaluations a table of its own.
TEST(SchemaTest, OlderStoresAreUpgradedKeepingEveryRow) {
  for (const int version : {1, 2}) {
    SCOPED_TRACE("from version " + std::to_string(version));
    TempStorePath file("v" + std::to_string(version));
    const std::string columns = kVersion3Columns;
    {
      Result<std::unique_ptr<sql::Database>> db =
          sql::Database::Open(file.path());
      ASSERT_TRUE(db.ok()) << db.status().ToString();
      ASSERT_TRUE(Migrate(**db, version).ok());
      const Status written = (*db)->Execute(
          "INSERT INTO runs VALUES (1, 5, x'0a00', 'text', '00000000000000ff',"
          " 'build', '2026-01-01T00:00:00.000Z', NULL, 'running');"
          "INSERT INTO individuals VALUES"
          " (1, 0, 0, 'random', x'0a0b0c', '0000000000000001', 3, 't0', 'ok',"
          "  '', 0.1000000000000000055511151231257827, 32, 6600, 0.25, 'h:1',"
          "  '00000000000000aa', 'e0'),"
          " (1, 1, 1, 'copy', x'0a0b0d', '0000000000000002', 3, 't1', NULL,"
          "  NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL),"
          " (1, 2, 1, 'sign', x'0a0b0e', '0000000000000003', 3, 't2', 'ok',"
          "  '', 2.5, 32, 6600, 0.5, 'h:2', '00000000000000bb', 'e2');"
          "INSERT INTO parents VALUES (1, 1, 0, 0), (1, 2, 0, 0);");
      ASSERT_TRUE(written.ok()) << written.ToString();
    }
    std::vector<std::vector<std::string>> before;
    {
      Result<std::unique_ptr<sql::Database>> db =
          sql::Database::Open(file.path(), /*read_only=*/true);
      ASSERT_TRUE(db.ok());
      Result<sql::Statement> select =
          (*db)->Prepare("SELECT " + columns + " FROM individuals ORDER BY id");
      ASSERT_TRUE(select.ok());
      for (;;) {
        Result<bool> row = select->Step();
        ASSERT_TRUE(row.ok());
        if (!*row) break;
        std::vector<std::string> values;
        for (int c = 0; c < 17; ++c) {
          values.push_back(select->IsNull(c) ? "NULL" : select->Text(c));
        }
        before.push_back(values);
      }
    }
    ASSERT_EQ(before.size(), 3u);
    ASSERT_EQ(UserVersion(file.path()), version);

    Result<std::unique_ptr<Store>> store = Store::Open(file.path());
    ASSERT_TRUE(store.ok()) << store.status().ToString();
    EXPECT_EQ(UserVersion(file.path()), kSchemaVersion);
    EXPECT_EQ(
        Rows(**store, "SELECT " + columns + " FROM individuals ORDER BY id"),
        before);
    EXPECT_EQ(Value(**store, "SELECT COUNT(*) FROM evaluations"), "2");
    EXPECT_EQ(Value(**store, "SELECT id FROM best"), "2");
    EXPECT_EQ(
        Rows(**store, "SELECT step, id FROM line_of_descent ORDER BY step"),
        (std::vector<std::vector<std::string>>{{"0", "2"}, {"1", "0"}}));
    EXPECT_EQ(Rows(**store,
                   "SELECT name, type, sql LIKE '%WITHOUT ROWID%'"
                   " FROM sqlite_schema WHERE name IN ('births',"
                   " 'evaluations', 'individuals', 'births_by_generation')"
                   " ORDER BY name"),
              (std::vector<std::vector<std::string>>{
                  {"births", "table", "0"},
                  {"births_by_generation", "index", "0"},
                  {"evaluations", "table", "1"},
                  {"individuals", "view", "0"}}));
    Result<std::vector<uint64_t>> pending = (*store)->Unevaluated(1);
    ASSERT_TRUE(pending.ok());
    EXPECT_EQ(*pending, std::vector<uint64_t>{1});
    for (const std::string& column : kBodyColumns) {
      EXPECT_EQ(Value(**store, "SELECT COUNT(*) FROM individuals WHERE " +
                                   column + " IS NOT NULL"),
                "0")
          << column;
    }
  }
}

// A store written by schema version 3 gains the body columns: NULL in
// every row it held, after the columns it had, which read as before; the
// queries refuse it until it is upgraded, naming the command that does.
// Then results record their bodies in it.
TEST(SchemaTest, Version3StoreGainsBodyColumnsNullInEveryOldRow) {
  TempStorePath file("v3");
  {
    Result<std::unique_ptr<sql::Database>> db =
        sql::Database::Open(file.path());
    ASSERT_TRUE(db.ok()) << db.status().ToString();
    ASSERT_TRUE(Migrate(**db, 3).ok());
    const Status written = (*db)->Execute(
        "INSERT INTO runs VALUES (1, 5, x'0a00', 'text', '00000000000000ff',"
        " 'build', '2026-01-01T00:00:00.000Z', NULL, 'running');"
        "INSERT INTO births VALUES"
        " (1, 0, 0, 'random', x'0a0b0c', '0000000000000001', 3, 't0'),"
        " (1, 1, 1, 'copy', x'0a0b0d', '0000000000000002', 3, 't1'),"
        " (1, 2, 1, 'sign', x'0a0b0e', '0000000000000003', 3, 't2'),"
        " (1, 3, 1, 'type', x'0a0b0f', '0000000000000004', 3, 't3');"
        "INSERT INTO evaluations VALUES"
        " (1, 0, 'ok', '', 0.1000000000000000055511151231257827, 32, 6600,"
        "  0.25, 'h:1', '00000000000000aa', 'e0'),"
        " (1, 2, 'ok', '', 2.5, 32, 6600, 0.5, 'h:2', '00000000000000bb',"
        "  'e2'),"
        " (1, 3, 'too_few_cells', 'too few', NULL, 1, 400, 0.01, 'h:2',"
        "  '0000000000000000', 'e3');"
        "INSERT INTO parents VALUES (1, 1, 0, 0), (1, 2, 0, 0), (1, 3, 0, 0);"
        "INSERT INTO generations VALUES (1, 0, 1, 'g0', 'c0', 1, 0, 0, 0.1,"
        "  0.1, 0.1);"
        "INSERT INTO members VALUES (1, 0, 0, 0);");
    ASSERT_TRUE(written.ok()) << written.ToString();
  }
  const std::vector<std::vector<std::string>> before =
      RawRows(file.path(), std::string("SELECT ") + kVersion3Columns +
                               " FROM individuals ORDER BY id");
  ASSERT_EQ(before.size(), 4u);
  std::vector<std::vector<std::string>> tables_before;
  for (const char* table :
       {"runs", "births", "parents", "generations", "members"}) {
    for (std::vector<std::string>& row :
         RawRows(file.path(),
                 std::string("SELECT * FROM ") + table + " ORDER BY 1, 2, 3")) {
      row.insert(row.begin(), table);
      tables_before.push_back(std::move(row));
    }
  }

  Result<std::unique_ptr<Store>> reader = Store::OpenForQueries(file.path());
  ASSERT_FALSE(reader.ok());
  EXPECT_TRUE(Contains(reader.status().message(), "schema version 3"))
      << reader.status().message();
  EXPECT_TRUE(Contains(reader.status().message(),
                       "`animat lineage upgrade --db " + file.path() + "`"))
      << reader.status().message();
  EXPECT_EQ(UserVersion(file.path()), 3);

  {
    Result<std::unique_ptr<Store>> store = Store::Open(file.path());
    ASSERT_TRUE(store.ok()) << store.status().ToString();
    EXPECT_EQ(UserVersion(file.path()), kSchemaVersion);
    EXPECT_EQ(Rows(**store, std::string("SELECT ") + kVersion3Columns +
                                " FROM individuals ORDER BY id"),
              before);
    std::vector<std::vector<std::string>> tables_after;
    for (const char* table :
         {"runs", "births", "parents", "generations", "members"}) {
      for (std::vector<std::string>& row :
           RawRows(file.path(), std::string("SELECT * FROM ") + table +
                                    " ORDER BY 1, 2, 3")) {
        row.insert(row.begin(), table);
        tables_after.push_back(std::move(row));
      }
    }
    EXPECT_EQ(tables_after, tables_before);
    // Version 3's columns first, in order, then the body's.
    std::vector<std::vector<std::string>> names =
        Rows(**store, "SELECT name FROM pragma_table_info('individuals')");
    ASSERT_EQ(names.size(), 27u);
    for (size_t c = 0; c < kBodyColumns.size(); ++c) {
      EXPECT_EQ(names[17 + c][0], kBodyColumns[c]);
    }
    EXPECT_EQ(names[16][0], "evaluated_at");
    // Then version 6's distance swum and energy, NULL in every old row.
    EXPECT_EQ(names[22][0], "distance");
    EXPECT_EQ(names[23][0], "energy");
    EXPECT_EQ(names[24][0], "max_overlap");  // Version 8's.
    EXPECT_EQ(names[25][0], "isa");          // Version 9's.
    EXPECT_EQ(names[26][0], "reused_from");  // Version 10's.
    EXPECT_EQ(Value(**store,
                    "SELECT COUNT(*) FROM individuals"
                    " WHERE distance IS NOT NULL OR energy IS NOT NULL"),
              "0");
    EXPECT_EQ(Rows(**store,
                   "SELECT id, springs, chambers, skin_edges, spread_major,"
                   " spread_minor FROM individuals ORDER BY id"),
              (std::vector<std::vector<std::string>>{
                  {"0", "NULL", "NULL", "NULL", "NULL", "NULL"},
                  {"1", "NULL", "NULL", "NULL", "NULL", "NULL"},
                  {"2", "NULL", "NULL", "NULL", "NULL", "NULL"},
                  {"3", "NULL", "NULL", "NULL", "NULL", "NULL"}}));
    EXPECT_EQ(Value(**store, "SELECT id FROM best"), "2");
    EXPECT_EQ(
        Rows(**store, "SELECT step, id FROM line_of_descent ORDER BY step"),
        (std::vector<std::vector<std::string>>{{"0", "2"}, {"1", "0"}}));

    // The pending individual's result, recorded now, has its body.
    Evaluation late = ::animat::testing::OkEvaluation(1, 0.75);
    *late.result.mutable_body() = ::animat::testing::MakeBody(6);
    ASSERT_TRUE((*store)->RecordEvaluations(1, {late}).ok());
    EXPECT_EQ(
        Rows(**store,
             "SELECT chambers, COUNT(*) FROM individuals"
             " GROUP BY chambers ORDER BY chambers"),
        (std::vector<std::vector<std::string>>{{"NULL", "3"}, {"6", "1"}}));
  }
  Result<std::unique_ptr<Store>> upgraded = Store::OpenForQueries(file.path());
  EXPECT_TRUE(upgraded.ok()) << upgraded.status().ToString();
}

// A store written by schema version 4 gains the configuration history: each
// run's configuration as it stands, from generation 0, saying that earlier
// changes were not recorded; the rest reads as before. Then changes are
// recorded after it.
TEST(SchemaTest, Version4StoreGainsItsRunsConfigurationsAsTheirHistory) {
  TempStorePath file("v4");
  const v1::RunConfig config = testing::SmallRunConfig(5);
  {
    Result<std::unique_ptr<sql::Database>> db =
        sql::Database::Open(file.path());
    ASSERT_TRUE(db.ok()) << db.status().ToString();
    ASSERT_TRUE(Migrate(**db, 4).ok());
    Result<sql::Statement> insert = (*db)->Prepare(
        "INSERT INTO runs VALUES (?, 5, ?, 'text', ?, ?,"
        " '2026-01-01T00:00:00.000Z', NULL, 'running')");
    ASSERT_TRUE(insert.ok());
    for (int64_t run : {1, 2}) {
      insert->Bind(1, run)
          .BindBlob(2, config.SerializeAsString())
          .Bind(3, "00000000000000f" + std::to_string(run))
          .Bind(4, "build " + std::to_string(run));
      ASSERT_TRUE(insert->Run().ok());
    }
  }
  std::vector<std::vector<std::string>> runs_before =
      RawRows(file.path(), "SELECT * FROM runs ORDER BY run_id");
  ASSERT_EQ(runs_before.size(), 2u);

  Result<std::unique_ptr<Store>> store = Store::Open(file.path());
  ASSERT_TRUE(store.ok()) << store.status().ToString();
  EXPECT_EQ(UserVersion(file.path()), kSchemaVersion);
  EXPECT_EQ(RawRows(file.path(), "SELECT * FROM runs ORDER BY run_id"),
            runs_before);
  EXPECT_EQ(Rows(**store,
                 "SELECT c.run_id, c.change, c.from_generation,"
                 " c.config = r.config AND c.config_text = r.config_text AND"
                 " c.config_hash = r.config_hash AND c.build_id = r.build_id"
                 " AND c.recorded_at = r.started_at"
                 " FROM run_configs c JOIN runs r USING (run_id)"
                 " ORDER BY c.run_id, c.change"),
            (std::vector<std::vector<std::string>>{{"1", "0", "0", "1"},
                                                   {"2", "0", "0", "1"}}));
  for (int64_t run : {1, 2}) {
    Result<std::vector<RunConfigRow>> history = (*store)->ConfigHistory(run);
    ASSERT_TRUE(history.ok()) << history.status().ToString();
    ASSERT_EQ(history->size(), 1u);
    EXPECT_EQ((*history)[0].from_generation, 0);
    EXPECT_TRUE(Contains((*history)[0].reason,
                         "earlier changes were not "
                         "recorded"))
        << (*history)[0].reason;
    EXPECT_EQ((*history)[0].config.SerializeAsString(),
              config.SerializeAsString());
  }
  ASSERT_TRUE(
      (*store)
          ->UpdateRunConfig(1, 7, testing::SmallRunConfig(6), "b", "--force")
          .ok());
  Result<std::vector<RunConfigRow>> history = (*store)->ConfigHistory(1);
  ASSERT_TRUE(history.ok());
  ASSERT_EQ(history->size(), 2u);
  EXPECT_EQ((*history)[1].change, 1);
  EXPECT_EQ((*history)[1].from_generation, 7);
}

// Two births of run 1, the first evaluated ok with a distance and energy.
constexpr char kTwoBirths[] =
    " (1, 0, 0, 'random', x'0a0b0c', '0000000000000001', 3, 't0'),"
    " (1, 1, 0, 'random', x'0a0b0d', '0000000000000002', 3, 't1');"
    "INSERT INTO evaluations (run_id, id, status, reason, fitness,"
    " distance, energy) VALUES (1, 0, 'ok', '', 0.5, 0.5, 12.0);";

// Writes a store of schema `version` holding run 1 and the births (and
// evaluations) of `rows`, SQL that follows "INSERT INTO births VALUES";
// returns its individuals as that version reads them (none on failure).
std::vector<std::vector<std::string>> OldStore(const TempStorePath& file,
                                               int version,
                                               const std::string& rows) {
  Result<std::unique_ptr<sql::Database>> db = sql::Database::Open(file.path());
  EXPECT_TRUE(db.ok()) << db.status().ToString();
  if (!db.ok()) return {};
  const Status migrated = Migrate(**db, version);
  EXPECT_TRUE(migrated.ok()) << migrated.ToString();
  const Status written = (*db)->Execute(
      "INSERT INTO runs VALUES (1, 5, x'0a00', 'text', '00000000000000ff',"
      " 'build', '2026-01-01T00:00:00.000Z', NULL, 'running');"
      "INSERT INTO births VALUES" +
      rows);
  EXPECT_TRUE(written.ok()) << written.ToString();
  db->reset();
  return RawRows(file.path(), "SELECT * FROM individuals ORDER BY id");
}

// A store written by schema version 6 gains the trials table, empty: its
// evaluations keep every column as they were; guidance results recorded
// after have their trials.
TEST(SchemaTest, Version6StoreGainsAnEmptyTrialsTable) {
  TempStorePath file("v6");
  const std::vector<std::vector<std::string>> before =
      OldStore(file, 6, kTwoBirths);
  ASSERT_EQ(before.size(), 2u);

  Result<std::unique_ptr<Store>> store = Store::Open(file.path());
  ASSERT_TRUE(store.ok()) << store.status().ToString();
  EXPECT_EQ(UserVersion(file.path()), kSchemaVersion);
  // Every column as before; later versions' columns follow, NULL.
  std::vector<std::vector<std::string>> after =
      Rows(**store, "SELECT * FROM individuals ORDER BY id");
  for (std::vector<std::string>& row : after) row.resize(before[0].size());
  EXPECT_EQ(after, before);
  EXPECT_EQ(Value(**store, "SELECT COUNT(*) FROM trials"), "0");

  Evaluation guided = ::animat::testing::OkEvaluation(1, 1.0);
  guided.result.add_source_distances(29.0);
  guided.result.add_source_distances(29.0);
  ASSERT_TRUE((*store)->RecordEvaluations(1, {guided}).ok());
  EXPECT_EQ(Rows(**store, "SELECT id, trial FROM trials ORDER BY trial"),
            (std::vector<std::vector<std::string>>{{"1", "0"}, {"1", "1"}}));
}

// After an upgrade of a store whose view individuals read `before`: its
// columns are `before`'s, then `added` in order, NULL in every old row.
void ExpectAddedColumnsNullInOldRows(
    Store& store, const std::vector<std::vector<std::string>>& before,
    const std::vector<std::string>& added) {
  ASSERT_FALSE(before.empty());
  const size_t old_columns = before[0].size();
  const std::vector<std::vector<std::string>> names =
      Rows(store, "SELECT name FROM pragma_table_info('individuals')");
  ASSERT_EQ(names.size(), old_columns + added.size());
  for (size_t c = 0; c < added.size(); ++c) {
    EXPECT_EQ(names[old_columns + c][0], added[c]);
  }
  std::vector<std::vector<std::string>> after =
      Rows(store, "SELECT * FROM individuals ORDER BY id");
  for (std::vector<std::string>& row : after) {
    ASSERT_EQ(row.size(), names.size());
    for (size_t c = old_columns; c < row.size(); ++c) {
      EXPECT_EQ(row[c], "NULL") << names[c][0];
    }
    row.resize(old_columns);
  }
  EXPECT_EQ(after, before);
}

// A store written by schema version 7 gains max_overlap, the last column of
// individuals, NULL in every old row; the other columns read as before, and
// results recorded after have it.
TEST(SchemaTest, Version7StoreGainsMaxOverlapNullInEveryOldRow) {
  TempStorePath file("v7");
  const std::vector<std::vector<std::string>> before =
      OldStore(file, 7, kTwoBirths);
  ASSERT_EQ(before.size(), 2u);

  Result<std::unique_ptr<Store>> store = Store::Open(file.path());
  ASSERT_TRUE(store.ok()) << store.status().ToString();
  EXPECT_EQ(UserVersion(file.path()), kSchemaVersion);
  ExpectAddedColumnsNullInOldRows(**store, before,
                                  {"max_overlap", "isa", "reused_from"});

  Evaluation folded = ::animat::testing::OkEvaluation(1, 1.0);
  folded.result.set_max_overlap(0.125);
  ASSERT_TRUE((*store)->RecordEvaluations(1, {folded}).ok());
  EXPECT_EQ(Value(**store, "SELECT MAX(max_overlap) FROM individuals"),
            "0.125");
}

// A store written by schema version 8 gains isa, the last column of
// individuals, NULL in every old row; the other columns read as before, and
// results recorded after have it (NULL when not known).
TEST(SchemaTest, Version8StoreGainsIsaNullInEveryOldRow) {
  TempStorePath file("v8");
  const std::vector<std::vector<std::string>> before =
      OldStore(file, 8,
               " (1, 0, 0, 'random', x'0a0b0c', '0000000000000001', 3, 't0'),"
               " (1, 1, 0, 'random', x'0a0b0d', '0000000000000002', 3, 't1'),"
               " (1, 2, 0, 'random', x'0a0b0e', '0000000000000003', 3, 't2');"
               "INSERT INTO evaluations (run_id, id, status, reason, fitness,"
               " max_overlap) VALUES (1, 0, 'ok', '', 0.5, 0.25);");
  ASSERT_EQ(before.size(), 3u);

  Result<std::unique_ptr<Store>> store = Store::Open(file.path());
  ASSERT_TRUE(store.ok()) << store.status().ToString();
  EXPECT_EQ(UserVersion(file.path()), kSchemaVersion);
  ExpectAddedColumnsNullInOldRows(**store, before, {"isa", "reused_from"});

  Evaluation wide = ::animat::testing::OkEvaluation(1, 1.0);
  wide.isa = "avx512";
  const Evaluation unknown = ::animat::testing::OkEvaluation(2, 2.0);
  ASSERT_TRUE((*store)->RecordEvaluations(1, {wide, unknown}).ok());
  EXPECT_EQ(Rows(**store, "SELECT id, isa FROM individuals ORDER BY id"),
            (std::vector<std::vector<std::string>>{
                {"0", "NULL"}, {"1", "avx512"}, {"2", "NULL"}}));
}

// A store written by schema version 9 gains reused_from, the last column
// of individuals, NULL in every old row (each of them was simulated); the
// other columns read as before.
TEST(SchemaTest, Version9StoreGainsReusedFromNullInEveryOldRow) {
  TempStorePath file("v9");
  const std::vector<std::vector<std::string>> before =
      OldStore(file, 9,
               " (1, 0, 0, 'random', x'0a0b0c', '0000000000000001', 3, 't0'),"
               " (1, 1, 0, 'random', x'0a0b0d', '0000000000000002', 3, 't1');"
               "INSERT INTO evaluations (run_id, id, status, reason, fitness,"
               " isa) VALUES (1, 0, 'ok', '', 0.5, 'avx2');");
  ASSERT_EQ(before.size(), 2u);

  Result<std::unique_ptr<Store>> store = Store::Open(file.path());
  ASSERT_TRUE(store.ok()) << store.status().ToString();
  EXPECT_EQ(UserVersion(file.path()), 10);
  ExpectAddedColumnsNullInOldRows(**store, before, {"reused_from"});
}

// An individual of a realistic genome (about 1 kB) costs about its size on
// disk: rows are not spilled into overflow pages of their own.
TEST(SchemaTest, IndividualsTakeAboutTheirOwnSizeOnDisk) {
  TempStorePath file("size");
  Result<std::unique_ptr<Store>> store = Store::Open(file.path());
  ASSERT_TRUE(store.ok()) << store.status().ToString();
  const int64_t run = MakeRun(**store);
  constexpr int kIndividuals = 2000;
  std::vector<NewIndividual> batch;
  std::vector<Evaluation> results;
  for (int id = 0; id < kIndividuals; ++id) {
    NewIndividual n = MakeIndividual(static_cast<uint64_t>(id), 0);
    n.genome = ::animat::testing::MakeGenome(45, static_cast<uint64_t>(id));
    batch.push_back(std::move(n));
    results.push_back(
        ::animat::testing::OkEvaluation(static_cast<uint64_t>(id), 1.0 + id));
  }
  ASSERT_TRUE((*store)->AddIndividuals(run, batch).ok());
  ASSERT_TRUE((*store)->RecordEvaluations(run, results).ok());
  const double content =
      std::stod(Value(**store,
                      "SELECT SUM(LENGTH(genome)) + 200.0 * COUNT(*)"
                      " FROM individuals"));
  const double used =
      std::stod(Value(**store,
                      "SELECT page_count * page_size"
                      " FROM pragma_page_count, pragma_page_size"));
  EXPECT_GT(content, kIndividuals * 800.0);  // Genomes of about 1 kB.
  EXPECT_LT(used, 2.0 * content) << "content " << content << " bytes";
}

TEST(SchemaTest, MigrateIsANoOpOnACurrentStore) {
  Result<std::unique_ptr<sql::Database>> db = sql::Database::Open("");
  ASSERT_TRUE(db.ok());
  ASSERT_TRUE(Migrate(**db).ok());
  const Status again = Migrate(**db);
  EXPECT_TRUE(again.ok()) << again.ToString();
}

TEST(SchemaTest, NewerVersionIsRefusedNamingBothVersions) {
  TempStorePath file("newer");
  const int newer = kSchemaVersion + 1;
  MakeVersionedFile(file.path(), newer);
  for (int attempt = 0; attempt < 2; ++attempt) {
    // The second attempt shows the refusal released the lock.
    Result<std::unique_ptr<Store>> store = Store::Open(file.path());
    ASSERT_FALSE(store.ok());
    const std::string& message = store.status().message();
    EXPECT_EQ(store.status().code(), StatusCode::kInvalidArgument) << message;
    EXPECT_TRUE(Contains(message, "version " + std::to_string(newer)))
        << message;
    EXPECT_TRUE(Contains(message, "up to " + std::to_string(kSchemaVersion)))
        << message;
    EXPECT_TRUE(Contains(message, file.path())) << message;
  }
  EXPECT_EQ(UserVersion(file.path()), newer);  // Left as it was.
}

TEST(LockTest, SecondOpenInTheSameProcessFailsSayingSo) {
  TempStorePath file("lock-same");
  Result<std::unique_ptr<Store>> first = Store::Open(file.path());
  ASSERT_TRUE(first.ok()) << first.status().ToString();
  Result<std::unique_ptr<Store>> second = Store::Open(file.path());
  ASSERT_FALSE(second.ok());
  const std::string& message = second.status().message();
  EXPECT_TRUE(Contains(message, file.path() + ".lock is locked")) << message;
  EXPECT_TRUE(Contains(message, "another master")) << message;
  // The first store is unaffected.
  EXPECT_TRUE((*first)->CreateRun(1, testing::SmallRunConfig(1), "b").ok());
}

TEST(LockTest, SecondOpenInAnotherProcessFailsSayingSo) {
  TempStorePath file("lock-other");
  Result<std::unique_ptr<Store>> first = Store::Open(file.path());
  ASSERT_TRUE(first.ok()) << first.status().ToString();
  const ChildReport child =
      RunInChild([&] { return OpenAndClose(file.path()); });
  EXPECT_EQ(child.exit_code, 1);
  EXPECT_TRUE(Contains(child.text, file.path() + ".lock is locked"))
      << child.text;
}

TEST(LockTest, LockIsReleasedWhenTheStoreIsDestroyed) {
  TempStorePath file("lock-release");
  {
    Result<std::unique_ptr<Store>> first = Store::Open(file.path());
    ASSERT_TRUE(first.ok()) << first.status().ToString();
  }
  const ChildReport child =
      RunInChild([&] { return OpenAndClose(file.path()); });
  EXPECT_EQ(child.exit_code, 0) << child.text;
  Result<std::unique_ptr<Store>> again = Store::Open(file.path());
  EXPECT_TRUE(again.ok()) << again.status().ToString();
}

TEST(LockTest, InMemoryStoresAreIndependentAndUnlocked) {
  std::unique_ptr<Store> a = MemoryStore();
  std::unique_ptr<Store> b = MemoryStore();
  ASSERT_NE(a, nullptr);
  ASSERT_NE(b, nullptr);
  MakeRun(*a);
  EXPECT_EQ(Value(*a, "SELECT COUNT(*) FROM runs"), "1");
  EXPECT_EQ(Value(*b, "SELECT COUNT(*) FROM runs"), "0");
}

TEST(OpenForQueriesTest, ReadsWhileAWriterHoldsTheLock) {
  TempStorePath file("query-live");
  Result<std::unique_ptr<Store>> writer = Store::Open(file.path());
  ASSERT_TRUE(writer.ok()) << writer.status().ToString();
  const int64_t run = MakeRun(**writer);
  ASSERT_TRUE((*writer)->AddIndividuals(run, {MakeIndividual(0, 0)}).ok());

  Result<std::unique_ptr<Store>> reader = Store::OpenForQueries(file.path());
  ASSERT_TRUE(reader.ok()) << reader.status().ToString();
  Result<std::vector<RunRow>> runs = (*reader)->Runs();
  ASSERT_TRUE(runs.ok()) << runs.status().ToString();
  EXPECT_EQ(runs->size(), 1u);
  Result<uint64_t> next = (*reader)->NextId(run);
  ASSERT_TRUE(next.ok());
  EXPECT_EQ(*next, 1u);

  // The reader sees what the writer commits later.
  ASSERT_TRUE((*writer)->AddIndividuals(run, {MakeIndividual(1, 0)}).ok());
  next = (*reader)->NextId(run);
  ASSERT_TRUE(next.ok());
  EXPECT_EQ(*next, 2u);
}

TEST(OpenForQueriesTest, ReadsAStoreNoWriterHasOpen) {
  TempStorePath file("query-closed");
  {
    Result<std::unique_ptr<Store>> writer = Store::Open(file.path());
    ASSERT_TRUE(writer.ok()) << writer.status().ToString();
    MakeRun(**writer);
  }
  Result<std::unique_ptr<Store>> reader = Store::OpenForQueries(file.path());
  ASSERT_TRUE(reader.ok()) << reader.status().ToString();
  Result<std::vector<RunRow>> runs = (*reader)->Runs();
  ASSERT_TRUE(runs.ok()) << runs.status().ToString();
  EXPECT_EQ(runs->size(), 1u);
}

TEST(OpenForQueriesTest, CannotWrite) {
  TempStorePath file("query-write");
  {
    Result<std::unique_ptr<Store>> writer = Store::Open(file.path());
    ASSERT_TRUE(writer.ok()) << writer.status().ToString();
  }
  Result<std::unique_ptr<Store>> reader = Store::OpenForQueries(file.path());
  ASSERT_TRUE(reader.ok()) << reader.status().ToString();
  EXPECT_FALSE((*reader)->CreateRun(1, testing::SmallRunConfig(1), "b").ok());
}

TEST(OpenForQueriesTest, RefusesAMissingFileWithoutCreatingIt) {
  TempStorePath file("query-missing");
  Result<std::unique_ptr<Store>> reader = Store::OpenForQueries(file.path());
  ASSERT_FALSE(reader.ok());
  EXPECT_EQ(reader.status().code(), StatusCode::kNotFound);
  EXPECT_TRUE(Contains(reader.status().message(), file.path()))
      << reader.status().message();
  EXPECT_NE(access(file.path().c_str(), F_OK), 0);
}

TEST(OpenForQueriesTest, RefusesANewerSchemaVersion) {
  TempStorePath file("query-newer");
  const int newer = kSchemaVersion + 1;
  MakeVersionedFile(file.path(), newer);
  Result<std::unique_ptr<Store>> reader = Store::OpenForQueries(file.path());
  ASSERT_FALSE(reader.ok());
  const std::string& message = reader.status().message();
  EXPECT_EQ(reader.status().code(), StatusCode::kInvalidArgument);
  EXPECT_TRUE(Contains(message, "version " + std::to_string(newer))) << message;
  EXPECT_TRUE(
      Contains(message, "reads version " + std::to_string(kSchemaVersion)))
      << message;
  EXPECT_TRUE(Contains(message, "newer")) << message;
}

TEST(OpenForQueriesTest, RefusesAnOlderSchemaVersionWithoutUpgradingIt) {
  TempStorePath file("query-older");
  { std::ofstream touch(file.path()); }  // Version 0.
  Result<std::unique_ptr<Store>> reader = Store::OpenForQueries(file.path());
  ASSERT_FALSE(reader.ok());
  const std::string& message = reader.status().message();
  EXPECT_TRUE(Contains(message, "version 0")) << message;
  EXPECT_TRUE(Contains(message, "upgrades")) << message;
  EXPECT_EQ(UserVersion(file.path()), 0);
}

TEST(UpgradeTest, BringsAnOlderStoreToThisSchemaAndSaysFromWhich) {
  TempStorePath file("upgrade-older");
  {
    Result<std::unique_ptr<sql::Database>> db =
        sql::Database::Open(file.path());
    ASSERT_TRUE(db.ok()) << db.status().ToString();
    ASSERT_TRUE(Migrate(**db, 2).ok());
  }
  Result<int> before = Store::Upgrade(file.path());
  ASSERT_TRUE(before.ok()) << before.status().ToString();
  EXPECT_EQ(*before, 2);
  EXPECT_EQ(UserVersion(file.path()), kSchemaVersion);
  before = Store::Upgrade(file.path());
  ASSERT_TRUE(before.ok()) << before.status().ToString();
  EXPECT_EQ(*before, kSchemaVersion);
}

TEST(UpgradeTest, RefusesAMissingFileWithoutCreatingIt) {
  TempStorePath file("upgrade-missing");
  Result<int> before = Store::Upgrade(file.path());
  ASSERT_FALSE(before.ok());
  EXPECT_EQ(before.status().code(), StatusCode::kNotFound);
  EXPECT_EQ(before.status().message(), file.path() + ": no such lineage store");
  EXPECT_FALSE(std::filesystem::exists(file.path()));
}

TEST(UpgradeTest, RefusesAFileThatIsNoLineageStore) {
  TempStorePath file("upgrade-other");
  { std::ofstream touch(file.path()); }  // Version 0.
  Result<int> before = Store::Upgrade(file.path());
  ASSERT_FALSE(before.ok());
  EXPECT_EQ(before.status().code(), StatusCode::kInvalidArgument);
  EXPECT_TRUE(Contains(before.status().message(), "not a lineage store"))
      << before.status().message();
  EXPECT_EQ(UserVersion(file.path()), 0);
}

TEST(UpgradeTest, RefusesAStoreAMasterHolds) {
  TempStorePath file("upgrade-held");
  Result<std::unique_ptr<Store>> master = Store::Open(file.path());
  ASSERT_TRUE(master.ok()) << master.status().ToString();
  Result<int> before = Store::Upgrade(file.path());
  ASSERT_FALSE(before.ok());
  EXPECT_TRUE(Contains(before.status().message(), "in use by another master"))
      << before.status().message();
}

// docs/lineage.md describes every table and view under a "### `name`"
// heading with a table whose rows start "| `column` | TYPE |" (TYPE only
// for tables). This keeps the page and schema.cc in step.
TEST(SchemaTest, DocumentationDescribesEveryTableViewAndColumn) {
  std::ifstream doc(std::string(ANIMAT_SOURCE_DIR) + "/docs/lineage.md");
  ASSERT_TRUE(doc) << "docs/lineage.md is missing";
  // name -> documented {column, type} rows, in order.
  std::map<std::string, std::vector<std::vector<std::string>>> documented;
  std::string current;
  std::string line;
  while (std::getline(doc, line)) {
    if (line.rfind("### `", 0) == 0) {
      const size_t end = line.find('`', 5);
      current = line.substr(5, end - 5);
      documented[current];
      continue;
    }
    if (line.rfind("## ", 0) == 0) current.clear();
    if (current.empty() || line.rfind("| `", 0) != 0) continue;
    const size_t end = line.find('`', 3);
    const std::string column = line.substr(3, end - 3);
    std::string type;
    const size_t bar = line.find('|', end);
    const size_t next = line.find('|', bar + 1);
    if (bar != std::string::npos && next != std::string::npos) {
      type = line.substr(bar + 1, next - bar - 1);
      type.erase(0, type.find_first_not_of(' '));
      type.erase(type.find_last_not_of(' ') + 1);
    }
    documented[current].push_back({column, type});
  }

  std::unique_ptr<Store> store = MemoryStore();
  ASSERT_NE(store, nullptr);
  std::map<std::string, std::vector<std::vector<std::string>>> actual;
  for (const std::vector<std::string>& object :
       Rows(*store,
            "SELECT name, type FROM sqlite_schema WHERE type IN ('table', "
            "'view') AND name NOT LIKE 'sqlite_%'")) {
    const bool view = object[1] == "view";
    std::vector<std::vector<std::string>>& columns = actual[object[0]];
    for (const std::vector<std::string>& c :
         Rows(*store, "SELECT name, type FROM pragma_table_info('" + object[0] +
                          "') ORDER BY cid")) {
      columns.push_back({c[0], view ? "" : c[1]});
    }
    // A view's columns have no declared type of their own: only their
    // names are compared.
    if (view && documented.count(object[0])) {
      for (std::vector<std::string>& c : documented[object[0]]) c[1].clear();
    }
  }
  EXPECT_EQ(documented, actual);
}

}  // namespace
}  // namespace animat::lineage
