// The dispatcher's last resort for a suspect: evaluating it alone, away
// from every worker. A worker that vanishes while holding an individual
// is no evidence against its genome (the machine was preempted, the
// process killed, a peer played dead), so after kMaxAttempts leases
// ended without a result the dispatcher asks an Isolation to evaluate the
// genome by itself; only an evaluation that crashes there too is recorded
// as `crashed` (docs/protocol.md, "Attempts and isolation").
//
// The dispatcher defines what it needs; master/run/child_isolation.h
// provides it with a child process per evaluation. Not thread-safe: the
// dispatcher's thread calls every method.
#ifndef ANIMAT_MASTER_DISPATCH_ISOLATION_H_
#define ANIMAT_MASTER_DISPATCH_ISOLATION_H_

#include <cstdint>
#include <string>
#include <vector>

#include "animat/v1/config.pb.h"
#include "animat/v1/protocol.pb.h"
#include "common/base/status.h"

namespace animat {

// How an isolated evaluation ended.
struct IsolatedOutcome {
  enum class Kind {
    kResult,     // It finished: `result` holds what it answered.
    kCrashed,    // It died of a crash (a fatal signal): the genome's doing.
    kUndecided,  // Neither (it could not run, was stopped, took too long).
  };
  uint64_t individual = 0;
  Kind kind = Kind::kUndecided;
  v1::WorkResult result;  // kResult only; not yet checked.
  std::string evaluator;  // "host:pid (isolated)", for the record.
  std::string how;        // E.g. "signal Segmentation fault", for the log.
};

class Isolation {
 public:
  virtual ~Isolation() = default;

  // Starts evaluating `item` (a serialised WorkItem, work_encoder.h) under
  // `config`, whose ConfigHash is `config_hash`. Fails, saying why, when
  // it cannot start; nothing is then under way for it.
  virtual Status Start(uint64_t individual, const std::string& item,
                       const v1::Config& config, uint64_t config_hash) = 0;
  // The evaluations that ended since the last call (never blocks).
  virtual std::vector<IsolatedOutcome> Finished() = 0;
  // Stops the evaluation of `individual`, if under way; it is not
  // reported.
  virtual void Cancel(uint64_t individual) = 0;
};

}  // namespace animat

#endif  // ANIMAT_MASTER_DISPATCH_ISOLATION_H_
