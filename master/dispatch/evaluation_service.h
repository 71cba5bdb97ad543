// What an evolutionary run needs of whoever evaluates its individuals:
// submit genomes, collect completions, tell when results are recorded.
// The Dispatcher (dispatcher.h) serves it with workers over ZeroMQ; a
// benchmark may wrap one (bench/null_scoring.h).
//
// Not thread-safe: one thread calls every method.
#ifndef ANIMAT_MASTER_DISPATCH_EVALUATION_SERVICE_H_
#define ANIMAT_MASTER_DISPATCH_EVALUATION_SERVICE_H_

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "animat/v1/config.pb.h"
#include "animat/v1/genome.pb.h"
#include "animat/v1/trace.pb.h"
#include "common/base/clock.h"
#include "common/base/status.h"
#include "common/protocol/genome_wire.h"

namespace animat {

// An individual whose evaluation ended.
struct Completion {
  uint64_t individual = 0;
  v1::EvaluationResult result;
  // "host:pid" of the worker that evaluated it; "host:pid (isolated)" for
  // a suspect evaluated alone (isolation.h).
  std::string worker;
  double wall_seconds = 0;  // On the worker.
  // The instruction-set path that evaluated it ("baseline", "avx2",
  // "avx512"); empty when not known (nothing simulated, a crash, an older
  // worker).
  std::string isa;
  int attempts = 0;  // Dispatches that ended without a result.
  // From a worker in null-evaluation mode (benchmarks only): the result is
  // NOT_EVALUATED and nothing was simulated.
  bool null_evaluation = false;
};

class EvaluationService {
 public:
  virtual ~EvaluationService() = default;

  // Queues an individual for evaluation; an individual already pending is
  // left as it is. The genome must be valid.
  virtual void Submit(uint64_t individual, const v1::Genome& genome) = 0;
  // The same with the genome serialised (protocol::SerializeGenome), as
  // the caller may already have it.
  virtual void Submit(uint64_t individual,
                      const protocol::SerializedGenome& genome) = 0;
  // Works for up to `timeout_ms` (of clock()'s time) and returns the
  // completions that came in, as soon as there are some.
  virtual std::vector<Completion> Poll(int timeout_ms) = 0;
  // Says that these completions' results are recorded: whoever keeps them
  // until then may forget them.
  virtual void Acknowledge(const std::vector<uint64_t>& individuals) = 0;
  // Individuals submitted and not completed.
  virtual size_t pending() const = 0;
  // The time the service keeps (valid while it lives).
  virtual const Clock& clock() const = 0;
  // Whether a result is a pure function of what a simulation reads of the
  // genome (EvaluationKey, under the service's configuration and build),
  // as a simulation's is. Then a run does not submit an offspring whose
  // genome has a parent generation member's evaluation key: it records
  // that member's evaluation for it (docs/lineage.md, reused_from). False
  // for stand-ins that depend on something else, such as the individual's
  // id.
  virtual bool results_follow_genome() const { return true; }
};

// An evaluation service that evaluates under several model configurations
// at once (the dispatcher, for a campaign's runs).
class MultiConfigService : public EvaluationService {
 public:
  // The index to submit under for `config` (one added before gives its
  // index again). Fails, saying why, beyond the service's limit.
  virtual Result<size_t> AddConfig(const v1::Config& config) = 0;
  // Submit, under configuration `config` (an index AddConfig gave).
  virtual void SubmitUnder(size_t config, uint64_t individual,
                           const protocol::SerializedGenome& genome) = 0;
};

}  // namespace animat

#endif  // ANIMAT_MASTER_DISPATCH_EVALUATION_SERVICE_H_
