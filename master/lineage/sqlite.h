// A thin RAII layer over SQLite's C API: a connection and prepared
// statements whose failures come back as Status values that name the file
// and say what is wrong with it in words ("out/x.db is a directory",
// "out/x.db: the store is read-only (file mode or directory
// permissions)"), never SQL: with ANIMAT_DEBUG_SQL set in the
// environment, a failed statement's SQL is appended for developers.
//
// Not thread-safe: one thread uses a Database and its statements.
#ifndef ANIMAT_MASTER_LINEAGE_SQLITE_H_
#define ANIMAT_MASTER_LINEAGE_SQLITE_H_

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>

#include "common/base/status.h"

struct sqlite3;
struct sqlite3_stmt;

namespace animat::sql {

class Statement;

// What the file system says is wrong with `path` as a database to open for
// reading only or also for writing: a directory, a missing or unwritable
// folder, a file this user may not read or write, a read-only file system.
// OK when nothing is (also for "" and ":memory:"); kNotFound for a missing
// file or folder, kIoError otherwise.
Status CheckDatabasePath(const std::string& path, bool read_only);

class Database {
 public:
  // Opens or creates the database file ("" or ":memory:" for a private
  // in-memory one); with `read_only`, opens an existing file for reading.
  // Fails as CheckDatabasePath does, and when a file to write is
  // read-only.
  static Result<std::unique_ptr<Database>> Open(const std::string& path,
                                                bool read_only = false);
  ~Database();
  Database(const Database&) = delete;
  Database& operator=(const Database&) = delete;

  // Runs one or more statements without results.
  Status Execute(std::string_view sql);
  // Prepares one statement; the Database must outlive it.
  Result<Statement> Prepare(std::string_view sql);
  // Like Prepare, but the statement is prepared once and kept by the
  // Database for later calls with the same text: the Statement returned
  // borrows it, and resets it (bindings cleared) when destroyed. While a
  // text's statement is borrowed, another call with that text prepares a
  // statement of its own.
  Result<Statement> Cached(std::string_view sql);

  int64_t last_insert_rowid() const;
  // Rows the last INSERT, UPDATE or DELETE on this connection changed (0
  // for an INSERT OR IGNORE that ignored its row).
  int64_t changes() const;
  const std::string& path() const { return path_; }
  sqlite3* handle() { return db_; }

 private:
  struct Kept {
    sqlite3_stmt* statement = nullptr;
    bool borrowed = false;
  };

  Database(sqlite3* db, std::string path) : db_(db), path_(std::move(path)) {}
  sqlite3* db_;
  std::string path_;
  std::map<std::string, Kept, std::less<>> kept_;  // By SQL text.
};

// A prepared statement: bind (1-based), step, read columns (0-based).
class Statement {
 public:
  Statement(Statement&& other) noexcept;
  Statement& operator=(Statement&& other) noexcept;
  ~Statement();

  Statement& Bind(int index, int64_t value);
  Statement& Bind(int index, double value);
  Statement& Bind(int index, std::string_view text);
  Statement& BindBlob(int index, std::string_view bytes);
  Statement& BindNull(int index);
  Statement& Bind(int index, std::optional<double> value);

  // Steps once: true with a row to read, false when done. Errors name the
  // database's file.
  Result<bool> Step();
  // Steps to completion, calling `row()` once for each row (it reads the
  // columns of the current row). `row` returns void or a Status; the first
  // failure, of a step or of `row`, ends the loop and is returned.
  template <typename RowFunction>
  Status ForEachRow(RowFunction&& row);
  // Steps to completion (for statements without rows) and resets.
  Status Run();
  // Ready for new bindings and steps.
  void Reset();

  bool IsNull(int column) const;
  int64_t Int(int column) const;
  double Double(int column) const;
  std::string Text(int column) const;
  std::string Blob(int column) const;

 private:
  friend class Database;
  Statement(sqlite3* db, sqlite3_stmt* statement, const std::string* path,
            bool* borrowed = nullptr)
      : db_(db), statement_(statement), path_(path), borrowed_(borrowed) {}
  // Finalizes an owned statement, resets and returns a borrowed one.
  void Release();
  sqlite3* db_;
  sqlite3_stmt* statement_;
  const std::string* path_;  // The Database's, for messages.
  bool* borrowed_;           // The Database's flag, for a borrowed statement.
};

template <typename RowFunction>
Status Statement::ForEachRow(RowFunction&& row) {
  for (;;) {
    Result<bool> more = Step();
    if (!more.ok()) return more.status();
    if (!*more) return Status::Ok();
    if constexpr (std::is_void_v<std::invoke_result_t<RowFunction&>>) {
      row();
    } else {
      Status status = row();
      if (!status.ok()) return status;
    }
  }
}

}  // namespace animat::sql

#endif  // ANIMAT_MASTER_LINEAGE_SQLITE_H_
