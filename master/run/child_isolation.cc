#include "master/run/child_isolation.h"

#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "animat/v1/isolation.pb.h"
#include "common/protocol/protocol.h"

namespace animat {
namespace {

// Signals that only a fault of the evaluation itself sends.
bool CrashSignal(int signal) {
  switch (signal) {
    case SIGSEGV:
    case SIGBUS:
    case SIGFPE:
    case SIGILL:
    case SIGABRT:
    case SIGSYS:
    case SIGTRAP:
      return true;
    default:
      return false;
  }
}

std::string HostName() {
  char name[256] = {};
  if (gethostname(name, sizeof(name) - 1) != 0) return "localhost";
  return name;
}

}  // namespace

Result<std::unique_ptr<ChildIsolation>> ChildIsolation::Create(
    ChildIsolationOptions options) {
  if (options.command.empty()) {
    return Status::InvalidArgument("no program to evaluate genomes alone");
  }
  return std::unique_ptr<ChildIsolation>(
      new ChildIsolation(std::move(options)));
}

Status ChildIsolation::MakeDirectory() {
  if (!directory_.empty()) return Status::Ok();
  const char* tmp = std::getenv("TMPDIR");
  std::string pattern =
      std::string(tmp != nullptr && *tmp != '\0' ? tmp : "/tmp") +
      "/animat-isolation-XXXXXX";
  if (mkdtemp(pattern.data()) == nullptr) {
    return Status::IoError("cannot make a directory like " + pattern +
                           " for evaluations alone");
  }
  directory_ = pattern;
  return Status::Ok();
}

ChildIsolation::~ChildIsolation() {
  children_.clear();  // Killed and reaped (~LocalProcess).
  if (directory_.empty()) return;
  std::error_code ignored;
  std::filesystem::remove_all(directory_, ignored);
}

std::string ChildIsolation::RequestPath(uint64_t individual) const {
  return directory_ + "/" + std::to_string(individual) + ".request";
}

std::string ChildIsolation::ResultPath(uint64_t individual) const {
  return directory_ + "/" + std::to_string(individual) + ".result";
}

Status ChildIsolation::Start(uint64_t individual, const std::string& item,
                             const v1::Config& config, uint64_t config_hash) {
  Cancel(individual);
  Status made = MakeDirectory();
  if (!made.ok()) return made;
  v1::IsolatedEvaluation request;
  request.set_build_id(protocol::BuildId());
  *request.mutable_config() = config;
  request.set_config_hash(config_hash);
  if (!request.mutable_item()->ParseFromString(item)) {
    return Status::InvalidArgument("the work item does not parse");
  }
  {
    std::ofstream out(RequestPath(individual),
                      std::ios::binary | std::ios::trunc);
    if (!out || !request.SerializeToOstream(&out) || !out.flush()) {
      return Status::IoError(RequestPath(individual) + ": cannot write");
    }
  }
  ProcessOptions process;
  process.argv = options_.command;
  process.argv.insert(process.argv.end(),
                      {"--evaluate-one", RequestPath(individual), "--result",
                       ResultPath(individual)});
  process.own_process_group = true;
  Result<std::unique_ptr<LocalProcess>> started = LocalProcess::Start(process);
  if (!started.ok()) {
    RemoveFiles(individual);
    return started.status();
  }
  Child& child = children_[individual];
  child.process = std::move(started).value();
  child.deadline =
      options_.clock->Now() + std::chrono::milliseconds(options_.time_limit_ms);
  return Status::Ok();
}

std::vector<IsolatedOutcome> ChildIsolation::Finished() {
  std::vector<IsolatedOutcome> outcomes;
  const Clock::TimePoint now = options_.clock->Now();
  for (auto it = children_.begin(); it != children_.end();) {
    LocalProcess& process = *it->second.process;
    if (process.Exited()) {
      outcomes.push_back(Outcome(it->first, process));
    } else if (now > it->second.deadline) {
      IsolatedOutcome outcome;
      outcome.individual = it->first;
      outcome.how = "still running after " +
                    std::to_string(options_.time_limit_ms) + " ms; stopped";
      outcomes.push_back(std::move(outcome));
    } else {
      ++it;
      continue;
    }
    RemoveFiles(it->first);
    it = children_.erase(it);  // A child still running is killed.
  }
  return outcomes;
}

IsolatedOutcome ChildIsolation::Outcome(uint64_t individual,
                                        const LocalProcess& process) {
  IsolatedOutcome outcome;
  outcome.individual = individual;
  outcome.evaluator =
      HostName() + ":" + std::to_string(process.pid()) + " (isolated)";
  outcome.how = process.Describe();
  if (CrashSignal(process.term_signal())) {
    outcome.kind = IsolatedOutcome::Kind::kCrashed;
    return outcome;
  }
  if (process.exit_code() != 0) return outcome;
  std::ifstream in(ResultPath(individual), std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (!in || !outcome.result.ParseFromString(bytes.str())) {
    outcome.how = "exit code 0 without a readable result";
    return outcome;
  }
  outcome.kind = IsolatedOutcome::Kind::kResult;
  return outcome;
}

void ChildIsolation::Cancel(uint64_t individual) {
  if (children_.erase(individual) != 0) RemoveFiles(individual);
}

void ChildIsolation::RemoveFiles(uint64_t individual) {
  std::error_code ignored;
  std::filesystem::remove(RequestPath(individual), ignored);
  std::filesystem::remove(ResultPath(individual), ignored);
}

}  // namespace animat
