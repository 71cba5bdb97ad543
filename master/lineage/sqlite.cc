#include "master/lineage/sqlite.h"

#include <sqlite3.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace animat::sql {
namespace {

// The folder holding `path` ("." for a bare file name).
std::string FolderOf(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}

// A URI naming `path` for sqlite3_open_v2 with SQLITE_OPEN_URI.
std::string FileUri(const std::string& path) {
  std::string uri = "file:";
  for (const char c : path) {
    if (c == '%' || c == '?' || c == '#') {
      char escaped[4];
      std::snprintf(escaped, sizeof(escaped), "%%%02X",
                    static_cast<unsigned char>(c));
      uri += escaped;
    } else {
      uri += c;
    }
  }
  return uri;
}

// With ANIMAT_DEBUG_SQL set in the environment, " [SQL: ...]" for
// developers; else nothing: messages are for people and name no SQL.
std::string SqlDetail(std::string_view sql) {
  if (std::getenv("ANIMAT_DEBUG_SQL") == nullptr || sql.empty()) return "";
  return " [SQL: " + std::string(sql) + "]";
}

// What failed, in words, for SQLite's result code `rc` on `path`.
Status Describe(const std::string& path, int rc, const char* sqlite_message,
                std::string_view sql) {
  std::string what;
  switch (rc & 0xff) {
    case SQLITE_READONLY:
      what = path +
             ": the store is read-only (file mode or directory permissions)";
      break;
    case SQLITE_CANTOPEN:
    case SQLITE_IOERR: {
      const Status found = CheckDatabasePath(path, /*read_only=*/false);
      what = found.ok() ? path + ": cannot read or write it (" +
                              std::string(sqlite_message) + ")"
                        : found.message();
      break;
    }
    case SQLITE_FULL:
      what = path + ": the disk is full";
      break;
    case SQLITE_CORRUPT:
      what = path + ": the file is damaged (" + sqlite_message + ")";
      break;
    case SQLITE_NOTADB:
      what = path + " is not a lineage store (not an SQLite database)";
      break;
    case SQLITE_BUSY:
    case SQLITE_LOCKED:
      what = path + ": locked by another process for longer than 5 s";
      break;
    default:
      what = path + ": " + sqlite_message;
  }
  return Status::IoError(what + SqlDetail(sql));
}

}  // namespace

Status CheckDatabasePath(const std::string& path, bool read_only) {
  if (path.empty() || path == ":memory:") return Status::Ok();
  const std::string folder = FolderOf(path);
  struct stat info;
  if (stat(path.c_str(), &info) == 0) {
    if (S_ISDIR(info.st_mode)) return Status::IoError(path + " is a directory");
    if (access(path.c_str(), read_only ? R_OK : R_OK | W_OK) != 0) {
      if (errno == EROFS) {
        return Status::IoError(path + ": the file system is read-only");
      }
      return Status::IoError(
          read_only ? path + ": this user may not read it (file mode)"
                    : path +
                          ": the store is read-only (file mode or directory "
                          "permissions)");
    }
    // A writer needs the folder for the -wal, -shm (and lock) files.
    if (!read_only && access(folder.c_str(), W_OK) != 0 &&
        (access((path + "-wal").c_str(), W_OK) != 0 ||
         access((path + "-shm").c_str(), W_OK) != 0)) {
      return Status::IoError(path + ": the folder " + folder +
                             " is not writable (a writer keeps " + path +
                             "-wal and -shm beside the store)");
    }
    return Status::Ok();
  }
  const int missing = errno;
  if (missing != ENOENT) {
    return Status::IoError(path + ": " + std::strerror(missing));
  }
  if (read_only) return Status::NotFound(path + " does not exist");
  if (stat(folder.c_str(), &info) != 0) {
    return Status::NotFound("cannot create " + path + ": the folder " + folder +
                            " does not exist");
  }
  if (!S_ISDIR(info.st_mode)) {
    return Status::NotFound("cannot create " + path + ": " + folder +
                            " is not a directory");
  }
  if (access(folder.c_str(), W_OK) != 0) {
    return Status::IoError("cannot create " + path + ": the folder " + folder +
                           " is not writable");
  }
  return Status::Ok();
}

Result<std::unique_ptr<Database>> Database::Open(const std::string& path,
                                                 bool read_only) {
  const std::string name = path.empty() ? ":memory:" : path;
  // The file system's answer first: SQLite's ("disk I/O error", "unable to
  // open database file") does not say what is wrong.
  Status usable = CheckDatabasePath(name, read_only);
  if (!usable.ok()) return usable;
  sqlite3* db = nullptr;
  int flags = (read_only ? SQLITE_OPEN_READONLY
                         : SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE) |
              SQLITE_OPEN_NOMUTEX;
  std::string target = name;
  // Reading a WAL store needs its -shm file, which SQLite cannot create in
  // a folder this user may not write. Without -wal and -shm no writer has
  // the store open (a writer keeps both while it runs), so the file is read
  // as it is.
  const std::string folder = FolderOf(name);
  if (read_only && name != ":memory:" && access(folder.c_str(), W_OK) != 0 &&
      access((name + "-wal").c_str(), F_OK) != 0 &&
      access((name + "-shm").c_str(), F_OK) != 0) {
    target = FileUri(name) + "?immutable=1";
    flags |= SQLITE_OPEN_URI;
  }
  const int rc = sqlite3_open_v2(target.c_str(), &db, flags, nullptr);
  if (rc != SQLITE_OK) {
    Status status =
        Describe(name, db != nullptr ? sqlite3_extended_errcode(db) : rc,
                 db != nullptr ? sqlite3_errmsg(db) : sqlite3_errstr(rc), "");
    sqlite3_close(db);
    return status;
  }
  // SQLite opens a file it may not write read-only without a word; a
  // writer would fail at its first write.
  if (!read_only && sqlite3_db_readonly(db, "main") == 1) {
    sqlite3_close(db);
    return Describe(name, SQLITE_READONLY, "", "");
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
    Status status =
        Describe(path_, sqlite3_extended_errcode(db_),
                 message != nullptr ? message : sqlite3_errmsg(db_), text);
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
    return Describe(path_, sqlite3_extended_errcode(db_), sqlite3_errmsg(db_),
                    sql);
  }
  return Statement(db_, statement, &path_);
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
  return Statement(db_, it->second.statement, &path_, &it->second.borrowed);
}

int64_t Database::last_insert_rowid() const {
  return sqlite3_last_insert_rowid(db_);
}

int64_t Database::changes() const { return sqlite3_changes64(db_); }

Statement::Statement(Statement&& other) noexcept
    : db_(other.db_),
      statement_(other.statement_),
      path_(other.path_),
      borrowed_(other.borrowed_) {
  other.statement_ = nullptr;
  other.borrowed_ = nullptr;
}

Statement& Statement::operator=(Statement&& other) noexcept {
  if (this != &other) {
    Release();
    db_ = other.db_;
    statement_ = other.statement_;
    path_ = other.path_;
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
  Status status = Describe(*path_, sqlite3_extended_errcode(db_),
                           sqlite3_errmsg(db_), sqlite3_sql(statement_));
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
