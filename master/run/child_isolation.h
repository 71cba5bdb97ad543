// The dispatcher's Isolation (master/dispatch/isolation.h) with a child
// process per evaluation: `animat-worker --evaluate-one REQUEST --result
// RESULT`, started through the spawner of local_workers.h in a process
// group of its own (so a terminal's Ctrl-C, meant for the master, does not
// pass for a crash), its request and result in a private temporary
// directory (made by the first evaluation: a master that needs none
// leaves nothing behind, even when killed).
//
// A child that exits 0 with a readable result gives that result; one that
// dies of a crash signal (SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT,
// SIGSYS, SIGTRAP) is a crash; anything else decides nothing: another exit
// code (the child could not read the request, or is of another build),
// another signal (SIGKILL, SIGTERM: someone stopped it), or a child still
// running after `time_limit_ms` of the clock (it is then killed).
//
// Not thread-safe: the dispatcher's thread uses it. Children still running
// when it is destroyed are killed and reaped, and the directory removed.
#ifndef ANIMAT_MASTER_RUN_CHILD_ISOLATION_H_
#define ANIMAT_MASTER_RUN_CHILD_ISOLATION_H_

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "common/base/clock.h"
#include "common/base/status.h"
#include "master/dispatch/isolation.h"
#include "master/run/local_workers.h"

namespace animat {

struct ChildIsolationOptions {
  // The program and its first arguments; "--evaluate-one REQUEST --result
  // RESULT" follow. Usually {WorkerBesideThisProgram()}.
  std::vector<std::string> command;
  // A child running longer than this (the dispatcher's lease) is stopped.
  int time_limit_ms = 10 * 60 * 1000;
  const Clock* clock = &RealClock();  // Not owned; must outlive this.
};

class ChildIsolation final : public Isolation {
 public:
  // kInvalidArgument without a command. The directory (under $TMPDIR,
  // else /tmp) is made by the first Start, which fails with kIoError when
  // it cannot.
  static Result<std::unique_ptr<ChildIsolation>> Create(
      ChildIsolationOptions options);
  ~ChildIsolation() override;

  Status Start(uint64_t individual, const std::string& item,
               const v1::Config& config, uint64_t config_hash) override;
  std::vector<IsolatedOutcome> Finished() override;
  void Cancel(uint64_t individual) override;

  // Evaluations under way.
  size_t running() const { return children_.size(); }

 private:
  struct Child {
    std::unique_ptr<LocalProcess> process;
    Clock::TimePoint deadline;
  };
  explicit ChildIsolation(ChildIsolationOptions options)
      : options_(std::move(options)) {}
  Status MakeDirectory();
  std::string RequestPath(uint64_t individual) const;
  std::string ResultPath(uint64_t individual) const;
  // The outcome of a child that has exited.
  IsolatedOutcome Outcome(uint64_t individual, const LocalProcess& process);
  void RemoveFiles(uint64_t individual);

  ChildIsolationOptions options_;
  std::string directory_;  // "" until the first Start.
  std::map<uint64_t, Child> children_;
};

}  // namespace animat

#endif  // ANIMAT_MASTER_RUN_CHILD_ISOLATION_H_
