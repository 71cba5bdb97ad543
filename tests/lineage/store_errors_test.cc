// What the lineage store says when its file cannot be used: the file's
// name and what is wrong with it, never SQL or SQLite's "disk I/O error".
//
// The read-only cases need a user that file modes apply to: run as root,
// they drop to uid and gid 65534 (nobody) in a forked child.
#include <fcntl.h>
#include <grp.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <string>

#include "master/lineage/sqlite.h"
#include "master/lineage/store.h"
#include "tests/lineage/lineage_test_util.h"

namespace animat::lineage {
namespace {

namespace fs = std::filesystem;

using ::animat::testing::MakeRun;

bool Contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// No SQL and none of SQLite's own words for these failures.
void ExpectNoSqlInside(const std::string& message) {
  for (const char* sql : {"SELECT", "UPDATE", "INSERT", "PRAGMA", "statement",
                          "disk I/O error", "unable to open"}) {
    EXPECT_FALSE(Contains(message, sql)) << sql << " in: " << message;
  }
}

// A fresh folder, open to every user (the child of RunAsOther reads and
// writes in it), removed with its contents on destruction.
class TempFolder {
 public:
  TempFolder()
      : path_(::testing::TempDir() + "/store-errors-" +
              std::to_string(getpid()) + "-" +
              ::testing::UnitTest::GetInstance()->current_test_info()->name()) {
    fs::remove_all(path_);
    fs::create_directories(path_);
    chmod(path_.c_str(), 0777);
  }
  ~TempFolder() {
    chmod(path_.c_str(), 0777);
    fs::remove_all(path_);
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

void MakeStore(const std::string& path) {
  Result<std::unique_ptr<Store>> store = Store::Open(path);
  ASSERT_TRUE(store.ok()) << store.status().ToString();
  MakeRun(**store);
}

struct ChildReport {
  int exit_code = -1;
  std::string text;
};

// Runs `body` in a forked child as a user without special rights (uid
// 65534 when this process is root); the child reports the message of the
// Status it returns and exits 0 for OK, 1 otherwise, 2 when it could not
// drop its rights.
ChildReport RunAsOther(const std::function<Status()>& body) {
  int fds[2];
  if (pipe(fds) != 0) {
    ADD_FAILURE() << "pipe failed";
    return {};
  }
  const pid_t pid = fork();
  if (pid == 0) {
    close(fds[0]);
    if (geteuid() == 0 &&
        (setgroups(0, nullptr) != 0 || setresgid(65534, 65534, 65534) != 0 ||
         setresuid(65534, 65534, 65534) != 0)) {
      _exit(2);
    }
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
  for (ssize_t n; (n = read(fds[0], buffer, sizeof(buffer))) > 0;) {
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

TEST(StoreErrorsTest, ADirectoryIsNamedAsOne) {
  TempFolder folder;
  const std::string dir = folder.path() + "/runs";
  fs::create_directories(dir);
  for (const std::string& path : {dir, dir + "/"}) {
    Result<std::unique_ptr<Store>> writer = Store::Open(path);
    ASSERT_FALSE(writer.ok());
    EXPECT_EQ(writer.status().message(), path + " is a directory");
    Result<std::unique_ptr<Store>> reader = Store::OpenForQueries(path);
    ASSERT_FALSE(reader.ok());
    EXPECT_EQ(reader.status().message(), path + " is a directory");
  }
  EXPECT_FALSE(fs::exists(dir + ".lock"));
}

TEST(StoreErrorsTest, AMissingFolderIsNamedNotTheLockFile) {
  TempFolder folder;
  const std::string missing = folder.path() + "/missing";
  const std::string path = missing + "/x.db";
  Result<std::unique_ptr<Store>> writer = Store::Open(path);
  ASSERT_FALSE(writer.ok());
  EXPECT_EQ(
      writer.status().message(),
      "cannot create " + path + ": the folder " + missing + " does not exist");
  Result<std::unique_ptr<Store>> reader = Store::OpenForQueries(path);
  ASSERT_FALSE(reader.ok());
  EXPECT_EQ(reader.status().code(), StatusCode::kNotFound);
  EXPECT_EQ(reader.status().message(), path + ": no such lineage store");
  EXPECT_FALSE(fs::exists(missing));
}

TEST(StoreErrorsTest, AFileThatIsNotADatabaseIsNamed) {
  TempFolder folder;
  const std::string path = folder.path() + "/notes.db";
  std::ofstream(path) << std::string(4096, 'x');
  for (bool query : {false, true}) {
    Result<std::unique_ptr<Store>> store =
        query ? Store::OpenForQueries(path) : Store::Open(path);
    ASSERT_FALSE(store.ok());
    EXPECT_EQ(store.status().message(),
              path + " is not a lineage store (not an SQLite database)");
  }
}

TEST(StoreErrorsTest, AReadOnlyFileIsRefusedAtOpenAndStillReadable) {
  TempFolder folder;
  const std::string path = folder.path() + "/x.db";
  MakeStore(path);
  ASSERT_EQ(chmod(path.c_str(), 0444), 0);
  const ChildReport writer = RunAsOther([&]() -> Status {
    Result<std::unique_ptr<Store>> store = Store::Open(path);
    return store.ok() ? Status::Ok() : store.status();
  });
  ASSERT_NE(writer.exit_code, 2) << "could not drop root's rights";
  EXPECT_EQ(writer.exit_code, 1);
  EXPECT_EQ(writer.text, path +
                             ": the store is read-only (file mode or directory "
                             "permissions)");
  ExpectNoSqlInside(writer.text);
  const ChildReport reader = RunAsOther([&]() -> Status {
    Result<std::unique_ptr<Store>> store = Store::OpenForQueries(path);
    if (!store.ok()) return store.status();
    Result<std::vector<RunRow>> runs = (*store)->Runs();
    return runs.ok() ? Status::Ok() : runs.status();
  });
  EXPECT_EQ(reader.exit_code, 0) << reader.text;
}

TEST(StoreErrorsTest, AFolderNotWritableIsNamedAndItsStoreStillReadable) {
  TempFolder folder;
  const std::string dir = folder.path() + "/archive";
  fs::create_directories(dir);
  const std::string path = dir + "/x.db";
  MakeStore(path);
  for (const char* suffix : {"-wal", "-shm", ".lock"}) {
    std::remove((path + suffix).c_str());
  }
  ASSERT_EQ(chmod(path.c_str(), 0666), 0);
  ASSERT_EQ(chmod(dir.c_str(), 0555), 0);
  const ChildReport writer = RunAsOther([&]() -> Status {
    Result<std::unique_ptr<Store>> store = Store::Open(path);
    return store.ok() ? Status::Ok() : store.status();
  });
  ASSERT_NE(writer.exit_code, 2) << "could not drop root's rights";
  EXPECT_EQ(writer.exit_code, 1);
  EXPECT_TRUE(
      Contains(writer.text, path + ": the folder " + dir + " is not writable"))
      << writer.text;
  ExpectNoSqlInside(writer.text);
  // SQLite cannot make the -shm file a WAL store is read with; with no
  // writer about (no -wal, no -shm), the file is read as it is.
  const ChildReport reader = RunAsOther([&]() -> Status {
    Result<std::unique_ptr<Store>> store = Store::OpenForQueries(path);
    if (!store.ok()) return store.status();
    Result<std::vector<RunRow>> runs = (*store)->Runs();
    if (!runs.ok()) return runs.status();
    return runs->size() == 1 ? Status::Ok() : Status::Internal("no run");
  });
  EXPECT_EQ(reader.exit_code, 0) << reader.text;
  chmod(dir.c_str(), 0777);
}

TEST(StoreErrorsTest, AFailedWriteNamesTheFileNotTheSql) {
  TempFolder folder;
  const std::string path = folder.path() + "/x.db";
  MakeStore(path);
  Result<std::unique_ptr<sql::Database>> db =
      sql::Database::Open(path, /*read_only=*/true);
  ASSERT_TRUE(db.ok()) << db.status().ToString();
  const std::string update = "UPDATE runs SET state = 'finished'";
  Result<sql::Statement> statement = (*db)->Prepare(update);
  ASSERT_TRUE(statement.ok()) << statement.status().ToString();
  const Status run = statement->Run();
  ASSERT_FALSE(run.ok());
  EXPECT_EQ(run.message(),
            path +
                ": the store is read-only (file mode or directory "
                "permissions)");
  const Status execute = (*db)->Execute(update);
  ASSERT_FALSE(execute.ok());
  EXPECT_EQ(execute.message(), run.message());

  // For developers, the SQL on request.
  ASSERT_EQ(setenv("ANIMAT_DEBUG_SQL", "1", 1), 0);
  const Status debug = statement->Run();
  unsetenv("ANIMAT_DEBUG_SQL");
  EXPECT_EQ(debug.message(), run.message() + " [SQL: " + update + "]");
}

}  // namespace
}  // namespace animat::lineage
