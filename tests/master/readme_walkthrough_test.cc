// The README's walkthrough (a master and workers started by hand, the
// master interrupted and resumed) run as written. Its fenced blocks are
// found by their marker comments (`<!-- walkthrough: NAME -->`) and run
// from a temporary directory in which `build/bin` and `configs` link to
// this build's programs and the repository's configurations; only the
// port changes, to a free one. The master and the workers run in the
// background; the master gets SIGINT once a generation is committed; the
// command it printed is run as printed; the workers must exit 0 by
// themselves; the closing query must answer; and the store must hold what
// a run never interrupted holds.
//
// The test reads a small part of the shell: one command a line (a `\` at
// the end continues it), words split at blanks, `#` comments, a trailing
// `&` (in the background) and `wait`. Anything else in a block fails it,
// so that a README edit cannot pass untried.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "tests/master/master_harness.h"

namespace animat::testing {
namespace {

// The endpoint the README's commands use; the test gives each run its own
// port instead.
constexpr char kReadmeAddress[] = "127.0.0.1:5555";

struct ShellCommand {
  std::vector<std::string> words;
  bool background = false;  // Ended with `&`.
  std::string text;         // As the README writes it, for messages.
};

// The lines of the fenced block that follows `<!-- walkthrough: name -->`
// in `readme`.
Result<std::vector<std::string>> Block(const std::string& readme,
                                       const std::string& name) {
  const std::string marker = "<!-- walkthrough: " + name + " -->\n";
  const size_t at = readme.find(marker);
  if (at == std::string::npos) {
    return Status::NotFound("README.md has no block marked " + marker);
  }
  if (readme.find(marker, at + 1) != std::string::npos) {
    return Status::InvalidArgument("README.md marks two blocks " + marker);
  }
  std::istringstream in(readme.substr(at + marker.size()));
  std::string line;
  if (!std::getline(in, line) || line.rfind("```", 0) != 0) {
    return Status::InvalidArgument("no fenced block right after " + marker);
  }
  std::vector<std::string> lines;
  while (std::getline(in, line)) {
    if (line.rfind("```", 0) == 0) return lines;
    lines.push_back(line);
  }
  return Status::InvalidArgument("the block after " + marker + "is not closed");
}

// `text` with the README's address replaced by 127.0.0.1:`port`.
std::string WithPort(std::string text, int port) {
  const std::string address = "127.0.0.1:" + std::to_string(port);
  for (size_t at = text.find(kReadmeAddress); at != std::string::npos;
       at = text.find(kReadmeAddress, at + address.size())) {
    text.replace(at, sizeof(kReadmeAddress) - 1, address);
  }
  return text;
}

// The commands of a block, the port replaced.
Result<std::vector<ShellCommand>> Commands(
    const std::vector<std::string>& lines, int port) {
  std::vector<ShellCommand> commands;
  std::string pending;
  for (const std::string& line : lines) {
    pending += line;
    if (!pending.empty() && pending.back() == '\\') {
      pending.back() = ' ';
      continue;
    }
    ShellCommand command;
    command.text = pending;
    std::istringstream words(WithPort(pending, port));
    pending.clear();
    for (std::string word; words >> word;) {
      if (word[0] == '#') break;
      if (word.find_first_of("'\"$;|<>`*?(){}~") != std::string::npos) {
        return Status::InvalidArgument("shell syntax this test does not run: " +
                                       command.text);
      }
      command.words.push_back(word);
    }
    if (!command.words.empty() && command.words.back() == "&") {
      command.words.pop_back();
      command.background = true;
    }
    if (command.words.empty()) {
      if (command.background) {
        return Status::InvalidArgument("a lone &: " + command.text);
      }
      continue;
    }
    commands.push_back(std::move(command));
  }
  if (!pending.empty()) {
    return Status::InvalidArgument("a block ends in a continued line");
  }
  return commands;
}

// The value after `flag` in `words`, or "".
std::string FlagValue(const std::vector<std::string>& words,
                      const std::string& flag) {
  for (size_t i = 0; i + 1 < words.size(); ++i) {
    if (words[i] == flag) return words[i + 1];
  }
  return "";
}

// A TCP port on loopback that nothing listens on (the kernel's choice).
int FreePort() {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) return -1;
  sockaddr_in address = {};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = 0;
  socklen_t size = sizeof(address);
  int port = -1;
  if (bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)) == 0 &&
      getsockname(fd, reinterpret_cast<sockaddr*>(&address), &size) == 0) {
    port = ntohs(address.sin_port);
  }
  close(fd);
  return port;
}

class ReadmeWalkthroughTest : public MasterTest {
 protected:
  // The README's relative paths resolve in the test's directory.
  void SetUp() override {
    MasterTest::SetUp();
    home_ = std::filesystem::current_path();
    std::filesystem::create_directories(Path("build"));
    std::filesystem::create_directory_symlink(ANIMAT_BIN_DIR,
                                              Path("build/bin"));
    std::filesystem::create_directory_symlink(
        std::string(ANIMAT_SOURCE_DIR) + "/configs", Path("configs"));
    std::filesystem::current_path(dir_);
  }
  void TearDown() override {
    std::filesystem::current_path(home_);
    MasterTest::TearDown();
  }

  // The commands of block `name`; a failure if it is missing or malformed.
  std::vector<ShellCommand> ReadCommands(const std::string& name) {
    Result<std::vector<std::string>> lines = Block(readme_, name);
    if (!lines.ok()) {
      ADD_FAILURE() << lines.status().message();
      return {};
    }
    Result<std::vector<ShellCommand>> commands = Commands(*lines, port_);
    if (!commands.ok()) {
      ADD_FAILURE() << name << ": " << commands.status().message();
      return {};
    }
    return std::move(commands).value();
  }

  static std::unique_ptr<ChildProcess> Start(const ShellCommand& command,
                                             ChildProcess::Lifetime lifetime) {
    return std::make_unique<ChildProcess>(
        std::filesystem::path(command.words[0]).filename().string(),
        command.words, lifetime);
  }

  std::filesystem::path home_;
  std::string readme_;
  int port_ = -1;
};

TEST_F(ReadmeWalkthroughTest, RunsAsWrittenAndGivesTheUninterruptedRun) {
#ifndef NDEBUG
  GTEST_SKIP() << "the walkthrough's run lasts seconds in an optimised "
                  "build, minutes in a sanitizer build";
#endif
  Result<std::string> readme =
      ReadFile(std::string(ANIMAT_SOURCE_DIR) + "/README.md");
  ASSERT_TRUE(readme.ok()) << readme.status().ToString();
  readme_ = *readme;
  port_ = FreePort();
  ASSERT_GT(port_, 0);

  // Terminal 1: the master, in the foreground there.
  const std::vector<ShellCommand> terminal1 = ReadCommands("terminal 1");
  ASSERT_EQ(terminal1.size(), 1u) << "terminal 1 runs the master alone";
  ASSERT_FALSE(terminal1[0].background) << terminal1[0].text;
  const std::string db = FlagValue(terminal1[0].words, "--db");
  const std::string config = FlagValue(terminal1[0].words, "--config");
  ASSERT_FALSE(db.empty()) << terminal1[0].text;
  ASSERT_FALSE(config.empty()) << terminal1[0].text;
  std::unique_ptr<ChildProcess> master =
      Start(terminal1[0], ChildProcess::Lifetime::kExitsByItself);
  ASSERT_TRUE(master->started());

  // Terminal 2: workers in the background, then (at the end) `wait`.
  const std::vector<ShellCommand> terminal2 = ReadCommands("terminal 2");
  ASSERT_FALSE(terminal2.empty());
  std::vector<std::unique_ptr<ChildProcess>> workers;
  for (const ShellCommand& command : terminal2) {
    if (command.words == std::vector<std::string>{"wait"}) continue;
    ASSERT_TRUE(command.background)
        << "terminal 2 would not go on past " << command.text;
    workers.push_back(Start(command, ChildProcess::Lifetime::kExitsByItself));
    ASSERT_TRUE(workers.back()->started());
  }
  ASSERT_FALSE(workers.empty());
  EXPECT_EQ(terminal2.back().words, std::vector<std::string>{"wait"})
      << "terminal 2 ends with `wait`, for the workers";

  // Ctrl-C once a generation is committed; the master prints the resume
  // command, as the README shows it.
  ASSERT_TRUE(AwaitStore(
      db, [](const Progress& p) { return p.complete_generations >= 1; },
      *master))
      << master->output();
  ASSERT_TRUE(master->Signal(SIGINT));
  ASSERT_TRUE(AwaitExit(*master, kStepWait, "Ctrl-C"));
  ASSERT_EQ(master->exit_code(), 0) << master->output();
  ASSERT_FALSE(ReadProgress(db).finished)
      << "the run ended before Ctrl-C: too short to interrupt";
  EXPECT_NE(master->standard_error().find("Z master: generation 0/"),
            std::string::npos)
      << "terminal 1 logs a line per generation\n"
      << master->output();
  Result<std::vector<std::string>> printed =
      Block(readme_, "terminal 1 prints");
  ASSERT_TRUE(printed.ok()) << printed.status().message();
  ASSERT_EQ(printed->size(), 1u);
  const std::string said = master->standard_output();
  EXPECT_EQ(said, WithPort((*printed)[0], port_) + "\n");

  // Terminal 1 again: the command the master printed, as printed.
  const std::string kHint = "stopped; resume with: ";
  ASSERT_EQ(said.rfind(kHint, 0), 0u) << said;
  Result<std::vector<ShellCommand>> resume = Commands(
      {said.substr(kHint.size(), said.find('\n') - kHint.size())}, port_);
  ASSERT_TRUE(resume.ok()) << resume.status().message();
  ASSERT_EQ(resume->size(), 1u) << said;
  std::unique_ptr<ChildProcess> resumed =
      Start((*resume)[0], ChildProcess::Lifetime::kExitsByItself);
  ASSERT_TRUE(AwaitExit(*resumed, kRunWait, "the resumed master"));
  ASSERT_EQ(resumed->exit_code(), 0) << resumed->output();
  EXPECT_EQ(resumed->standard_output().rfind("finished", 0), 0u)
      << resumed->output();

  // Terminal 2's `wait` ends: every worker exits 0 by itself.
  for (const std::unique_ptr<ChildProcess>& worker : workers) {
    ASSERT_TRUE(AwaitExit(*worker, kStepWait, "a worker, the run finished"));
    EXPECT_EQ(worker->exit_code(), 0) << worker->output();
  }

  // The closing query answers.
  const std::vector<ShellCommand> end = ReadCommands("the end");
  ASSERT_FALSE(end.empty());
  for (const ShellCommand& command : end) {
    ASSERT_FALSE(command.background) << command.text;
    std::unique_ptr<ChildProcess> query =
        Start(command, ChildProcess::Lifetime::kExitsByItself);
    ASSERT_TRUE(AwaitExit(*query, kStepWait, command.text));
    EXPECT_EQ(query->exit_code(), 0) << query->output();
    EXPECT_NE(query->standard_output().find("id: "), std::string::npos)
        << command.text << ":\n"
        << query->output();
  }

  // The same individuals as the run made at once.
  const std::string reference = Path("reference.db");
  RunToEnd(config, reference, /*workers=*/2);
  if (HasFatalFailure()) return;
  EXPECT_TRUE(ReadProgress(db).finished) << ReadProgress(db).ToString();
  ExpectSameContents(ReadStoreContents(reference), ReadStoreContents(db));
}

}  // namespace
}  // namespace animat::testing
