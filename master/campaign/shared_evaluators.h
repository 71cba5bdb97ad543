// Many runs' evaluations through one MultiConfigService (the dispatcher,
// and so one pool of workers), each run under its own model configuration.
// Each run gets a lane: an EvaluationService
// of its own that the run's thread uses exactly as a lone run uses the
// dispatcher. One thread pumps: it hands what the lanes submitted and
// acknowledged to the service, polls it, and routes each completion back
// to its lane.
//
// An individual travels as a key, its lane's index times 2^kIdBits plus
// its id in its run, so the same id in two runs are two individuals; the
// worker never sees the difference (an evaluation depends on the genome
// and the model only). Ids of kIdBits bits or more are refused: the lane's
// error() says so, and nothing of it is submitted.
//
// The service sees the runs' individuals in the order their submissions
// reached the pump; each run's lineage does not depend on that order
// (evolution_run.h), so a campaign's run records what the run made alone
// records.
//
// Thread-safe as stated per method: AddLane and Pump on one thread (the
// service's), each lane's methods on the thread of its run.
#ifndef ANIMAT_MASTER_CAMPAIGN_SHARED_EVALUATORS_H_
#define ANIMAT_MASTER_CAMPAIGN_SHARED_EVALUATORS_H_

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "common/base/status.h"
#include "master/dispatch/evaluation_service.h"

namespace animat {

class SharedEvaluators {
 public:
  // Ids in a run below 2^kIdBits; up to 2^(63 - kIdBits) lanes.
  static constexpr int kIdBits = 44;

  // `service` is not owned and must outlive this; only the pumping thread
  // calls it.
  explicit SharedEvaluators(MultiConfigService* service);
  ~SharedEvaluators();
  SharedEvaluators(const SharedEvaluators&) = delete;
  SharedEvaluators& operator=(const SharedEvaluators&) = delete;

  // A new lane whose individuals are evaluated under `config` (an index
  // the service's AddConfig gave), valid while this lives. The pumping
  // thread, before any run uses its lane.
  EvaluationService* AddLane(size_t config);

  // Hands the lanes' submissions and acknowledgements to the service,
  // polls it for up to `timeout_ms` and routes the completions, returning
  // as soon as some came. The service is polled a millisecond at a time,
  // with what the lanes submitted meanwhile handed over between, so that a
  // submission waits about a millisecond, not the whole timeout. The
  // pumping thread.
  void Pump(int timeout_ms);

  // The first error of lane `index` (an id out of range), or OK. Any
  // thread.
  Status error(size_t index) const;

 private:
  class Lane;

  // Hands the lanes' submissions and acknowledgements to the service.
  void HandOver();

  mutable std::mutex mutex_;
  struct Submission {
    size_t config;
    uint64_t key;
    protocol::SerializedGenome genome;
  };

  MultiConfigService* service_;
  std::vector<std::unique_ptr<Lane>> lanes_;
  // Waiting for the next pump (mutex_).
  std::deque<Submission> submitted_;
  std::vector<uint64_t> acknowledged_;
};

}  // namespace animat

#endif  // ANIMAT_MASTER_CAMPAIGN_SHARED_EVALUATORS_H_
