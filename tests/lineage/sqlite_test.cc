// The SQLite layer's kept statements (sql::Database::Cached): prepared
// once, lent out, and returned reset, with no read left open; and the row
// loop (Statement::ForEachRow).
#include "master/lineage/sqlite.h"

#include <gtest/gtest.h>
#include <sqlite3.h>

#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

namespace animat::sql {
namespace {

class CachedStatementTest : public ::testing::Test {
 protected:
  void SetUp() override {
    Result<std::unique_ptr<Database>> db = Database::Open("");
    ASSERT_TRUE(db.ok()) << db.status().ToString();
    db_ = std::move(db).value();
    ASSERT_TRUE(db_->Execute("CREATE TABLE t (k INTEGER PRIMARY KEY, v TEXT);"
                             "INSERT INTO t VALUES (1, 'a'), (2, 'b'), "
                             "(3, 'c');")
                    .ok());
  }

  // Statements of the connection that are part-way through a step.
  int Busy() {
    int busy = 0;
    for (sqlite3_stmt* s = sqlite3_next_stmt(db_->handle(), nullptr);
         s != nullptr; s = sqlite3_next_stmt(db_->handle(), s)) {
      busy += sqlite3_stmt_busy(s) != 0;
    }
    return busy;
  }

  // Prepared statements of the connection.
  int Prepared() {
    int count = 0;
    for (sqlite3_stmt* s = sqlite3_next_stmt(db_->handle(), nullptr);
         s != nullptr; s = sqlite3_next_stmt(db_->handle(), s)) {
      ++count;
    }
    return count;
  }

  std::unique_ptr<Database> db_;
};

constexpr const char* kSelect = "SELECT v FROM t WHERE k >= ? ORDER BY k";

TEST_F(CachedStatementTest, IsPreparedOnceForItsText) {
  for (int i = 0; i < 3; ++i) {
    Result<Statement> select = db_->Cached(kSelect);
    ASSERT_TRUE(select.ok()) << select.status().ToString();
  }
  EXPECT_EQ(Prepared(), 1);
  Result<Statement> other = db_->Cached("SELECT COUNT(*) FROM t");
  ASSERT_TRUE(other.ok());
  EXPECT_EQ(Prepared(), 2);
}

TEST_F(CachedStatementTest, ComesBackResetWithBindingsCleared) {
  {
    Result<Statement> select = db_->Cached(kSelect);
    ASSERT_TRUE(select.ok());
    select->Bind(1, int64_t{3});
    Result<bool> row = select->Step();
    ASSERT_TRUE(row.ok() && *row);
    EXPECT_EQ(select->Text(0), "c");
    EXPECT_EQ(Busy(), 1);  // Dropped part-way through.
  }
  EXPECT_EQ(Busy(), 0);  // No read left open.
  Result<Statement> again = db_->Cached(kSelect);
  ASSERT_TRUE(again.ok());
  // An unbound parameter is NULL: `k >= NULL` matches nothing.
  Result<bool> row = again->Step();
  ASSERT_TRUE(row.ok());
  EXPECT_FALSE(*row);
  again->Reset();
  again->Bind(1, int64_t{1});
  std::string all;
  for (Result<bool> r = again->Step(); r.ok() && *r; r = again->Step()) {
    all += again->Text(0);
  }
  EXPECT_EQ(all, "abc");
}

TEST_F(CachedStatementTest, ATextLentOutGetsAStatementOfItsOwn) {
  Result<Statement> outer = db_->Cached(kSelect);
  ASSERT_TRUE(outer.ok());
  outer->Bind(1, int64_t{1});
  std::string pairs;
  for (Result<bool> r = outer->Step(); r.ok() && *r; r = outer->Step()) {
    Result<Statement> inner = db_->Cached(kSelect);  // Same text, nested.
    ASSERT_TRUE(inner.ok());
    inner->Bind(1, int64_t{3});
    Result<bool> row = inner->Step();
    ASSERT_TRUE(row.ok() && *row);
    pairs += outer->Text(0) + inner->Text(0) + " ";
  }
  EXPECT_EQ(pairs, "ac bc cc ");
  EXPECT_EQ(Prepared(), 1);  // The nested one was finalized.
}

TEST_F(CachedStatementTest, MovedStatementReturnsItOnce) {
  {
    Result<Statement> select = db_->Cached(kSelect);
    ASSERT_TRUE(select.ok());
    Statement moved = std::move(select).value();
    moved.Bind(1, int64_t{2});
    Result<bool> row = moved.Step();
    ASSERT_TRUE(row.ok() && *row);
    EXPECT_EQ(moved.Text(0), "b");
  }
  EXPECT_EQ(Busy(), 0);
  // Lent out again (not prepared anew): it was returned.
  Result<Statement> again = db_->Cached(kSelect);
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(Prepared(), 1);
}

// SQLite's reason, without the SQL; the SQL only for developers who ask.
TEST_F(CachedStatementTest, BadSqlFailsSayingWhyAndNamesItOnRequest) {
  Result<Statement> bad = db_->Cached("SELECT v FROM nowhere");
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().message(), ":memory:: no such table: nowhere");
  EXPECT_EQ(Prepared(), 0);
  ASSERT_EQ(setenv("ANIMAT_DEBUG_SQL", "1", 1), 0);
  Result<Statement> debug = db_->Cached("SELECT v FROM nowhere");
  unsetenv("ANIMAT_DEBUG_SQL");
  ASSERT_FALSE(debug.ok());
  EXPECT_NE(debug.status().message().find("[SQL: SELECT v FROM nowhere]"),
            std::string::npos)
      << debug.status().ToString();
}

TEST_F(CachedStatementTest, KeepsWorkingAfterTheSchemaChanges) {
  {
    Result<Statement> select = db_->Cached(kSelect);
    ASSERT_TRUE(select.ok());
  }
  ASSERT_TRUE(db_->Execute("ALTER TABLE t ADD COLUMN w INTEGER;"
                           "INSERT INTO t (k, v) VALUES (4, 'd');")
                  .ok());
  Result<Statement> select = db_->Cached(kSelect);
  ASSERT_TRUE(select.ok());
  select->Bind(1, int64_t{4});
  Result<bool> row = select->Step();
  ASSERT_TRUE(row.ok() && *row) << (row.ok() ? "" : row.status().ToString());
  EXPECT_EQ(select->Text(0), "d");
}

TEST_F(CachedStatementTest, ForEachRowCallsTheRowFunctionForEveryRowInOrder) {
  Result<Statement> select = db_->Cached(kSelect);
  ASSERT_TRUE(select.ok());
  select->Bind(1, int64_t{2});
  std::vector<std::string> seen;
  const Status status =
      select->ForEachRow([&] { seen.push_back(select->Text(0)); });
  ASSERT_TRUE(status.ok()) << status.ToString();
  EXPECT_EQ(seen, (std::vector<std::string>{"b", "c"}));
}

TEST_F(CachedStatementTest, ForEachRowStopsAtTheRowFunctionsFailure) {
  Result<Statement> select = db_->Cached(kSelect);
  ASSERT_TRUE(select.ok());
  select->Bind(1, int64_t{1});
  std::vector<std::string> seen;
  const Status status = select->ForEachRow([&]() -> Status {
    seen.push_back(select->Text(0));
    if (select->Text(0) == "b") return Status::InvalidArgument("row b");
    return Status::Ok();
  });
  EXPECT_EQ(status.code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(status.message(), "row b");
  EXPECT_EQ(seen, (std::vector<std::string>{"a", "b"}));
}

TEST_F(CachedStatementTest, ForEachRowReturnsAFailedStep) {
  // The second row's value overflows a 64-bit integer: SQLite fails the
  // step that computes it.
  Result<Statement> select = db_->Prepare(
      "SELECT abs(CASE k WHEN 2 THEN -9223372036854775807 - 1 ELSE k END)"
      " FROM t ORDER BY k");
  ASSERT_TRUE(select.ok());
  int rows = 0;
  const Status status = select->ForEachRow([&] { ++rows; });
  EXPECT_FALSE(status.ok());
  EXPECT_NE(status.message().find("overflow"), std::string::npos)
      << status.ToString();
  EXPECT_EQ(rows, 1);
}

}  // namespace
}  // namespace animat::sql
