#include "master/lineage/sqlite.h"

#include <sqlite3.h>

namespace animat::sql {
namespace {

Status Error(sqlite3* db, std::string_view what) {
  return Status::IoError(std::string(what) + ": " + sqlite3_errmsg(db));
}

}  // namespace

Result<std::unique_ptr<Database>> Database::Open(const std::string& path,
                                                 bool read_only) {
  sqlite3* db = nullptr;
  const std::string name = path.empty() ? ":memory:" : path;
  const int flags = (read_only ? SQLITE_OPEN_READONLY
                               : SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE) |
                    SQLITE_OPEN_NOMUTEX;
  const int rc = sqlite3_open_v2(name.c_str(), &db, flags, nullptr);
  if (rc != SQLITE_OK) {
    Status status = Status::IoError(
        name + ": cannot open: " +
        (db != nullptr ? sqlite3_errmsg(db) : sqlite3_errstr(rc)));
    sqlite3_close(db);
    return status;
  }
  sqlite3_busy_timeout(db, 5000);
  sqlite3_extended_result_codes(db, 1);
  return std::unique_ptr<Database>(new Database(db, name));
}

Database::~Database() {
  for (auto& [sql, kept] : kept_) sqlite3_finalize(kept.statement);
  sqlite3_close(db_);
}

Status Database::Execute(std::string_view sql) {
  char* message = nullptr;
  const std::string text(sql);
  if (sqlite3_exec(db_, text.c_str(), nullptr, nullptr, &message) !=
      SQLITE_OK) {
    Status status = Status::IoError(path_ + ": " +
                                    (message != nullptr ? message : "error") +
                                    " in: " + text.substr(0, 80));
    sqlite3_free(message);
    return status;
  }
  return Status::Ok();
}

Result<Statement> Database::Prepare(std::string_view sql) {
  sqlite3_stmt* statement = nullptr;
  if (sqlite3_prepare_v3(db_, sql.data(), static_cast<int>(sql.size()),
                         SQLITE_PREPARE_PERSISTENT, &statement,
                         nullptr) != SQLITE_OK) {
    return Error(db_, path_ + ": cannot prepare \"" +
                          std::string(sql.substr(0, 80)) + "\"");
  }
  return Statement(db_, statement);
}

Result<Statement> Database::Cached(std::string_view sql) {
  auto it = kept_.find(sql);
  if (it == kept_.end()) {
    Result<Statement> prepared = Prepare(sql);
    if (!prepared.ok()) return prepared.status();
    it = kept_.emplace(std::string(sql), Kept{prepared->statement_, false})
             .first;
    prepared->statement_ = nullptr;  // Now the Database's.
  }
  if (it->second.borrowed) return Prepare(sql);
  it->second.borrowed = true;
  return Statement(db_, it->second.statement, &it->second.borrowed);
}

int64_t Database::last_insert_rowid() const {
  return sqlite3_last_insert_rowid(db_);
}

Statement::Statement(Statement&& other) noexcept
    : db_(other.db_), statement_(other.statement_), borrowed_(other.borrowed_) {
  other.statement_ = nullptr;
  other.borrowed_ = nullptr;
}

Statement& Statement::operator=(Statement&& other) noexcept {
  if (this != &other) {
    Release();
    db_ = other.db_;
    statement_ = other.statement_;
    borrowed_ = other.borrowed_;
    other.statement_ = nullptr;
    other.borrowed_ = nullptr;
  }
  return *this;
}

Statement::~Statement() { Release(); }

void Statement::Release() {
  if (borrowed_ != nullptr) {
    Reset();
    *borrowed_ = false;
    borrowed_ = nullptr;
  } else {
    sqlite3_finalize(statement_);
  }
  statement_ = nullptr;
}

Statement& Statement::Bind(int index, int64_t value) {
  sqlite3_bind_int64(statement_, index, value);
  return *this;
}

Statement& Statement::Bind(int index, double value) {
  sqlite3_bind_double(statement_, index, value);
  return *this;
}

Statement& Statement::Bind(int index, std::string_view text) {
  sqlite3_bind_text(statement_, index, text.data(),
                    static_cast<int>(text.size()), SQLITE_TRANSIENT);
  return *this;
}

Statement& Statement::BindBlob(int index, std::string_view bytes) {
  sqlite3_bind_blob(statement_, index, bytes.data(),
                    static_cast<int>(bytes.size()), SQLITE_TRANSIENT);
  return *this;
}

Statement& Statement::BindNull(int index) {
  sqlite3_bind_null(statement_, index);
  return *this;
}

Statement& Statement::Bind(int index, std::optional<double> value) {
  if (value) return Bind(index, *value);
  return BindNull(index);
}

Result<bool> Statement::Step() {
  const int rc = sqlite3_step(statement_);
  if (rc == SQLITE_ROW) return true;
  if (rc == SQLITE_DONE) return false;
  Status status =
      Error(db_, std::string("statement \"") +
                     std::string(sqlite3_sql(statement_)).substr(0, 80) + "\"");
  sqlite3_reset(statement_);
  return status;
}

Status Statement::Run() {
  Result<bool> row = Step();
  while (row.ok() && *row) row = Step();
  Reset();
  return row.ok() ? Status::Ok() : row.status();
}

void Statement::Reset() {
  sqlite3_reset(statement_);
  sqlite3_clear_bindings(statement_);
}

bool Statement::IsNull(int column) const {
  return sqlite3_column_type(statement_, column) == SQLITE_NULL;
}

int64_t Statement::Int(int column) const {
  return sqlite3_column_int64(statement_, column);
}

double Statement::Double(int column) const {
  return sqlite3_column_double(statement_, column);
}

std::string Statement::Text(int column) const {
  const unsigned char* text = sqlite3_column_text(statement_, column);
  return text != nullptr ? std::string(reinterpret_cast<const char*>(text),
                                       sqlite3_column_bytes(statement_, column))
                         : std::string();
}

std::string Statement::Blob(int column) const {
  const void* blob = sqlite3_column_blob(statement_, column);
  return blob != nullptr ? std::string(static_cast<const char*>(blob),
                                       sqlite3_column_bytes(statement_, column))
                         : std::string();
}

}  // namespace animat::sql
