// A pool of threads that evaluate work items (the worker's compute side).
//
// The session thread submits items and takes finished results; the pool
// signals "something finished" on an eventfd the session thread polls
// together with its socket. Submit, TakeFinished, Abandon and the
// destructor must be called from one thread (the session's); evaluation
// happens on the pool's own threads. Evaluations share nothing (a fresh
// simulation each), so results do not depend on the thread count.
#ifndef ANIMAT_WORKER_EVALUATION_POOL_H_
#define ANIMAT_WORKER_EVALUATION_POOL_H_

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

#include "animat/v1/protocol.pb.h"
#include "common/evaluation/model_config.h"
#include "worker/null_delay.h"

namespace animat {

// Evaluates one item with a fresh simulation, on the calling thread: its
// genome validated first (an invalid one gives INVALID_GENOME with the
// reason), a reason longer than the protocol takes cut to
// kMaxReasonBytes, and the wall time measured.
v1::WorkResult EvaluateItem(const v1::WorkItem& item,
                            const ModelConfig& config);

class EvaluationPool {
 public:
  // `threads` >= 1. With `null_evaluation` nothing is simulated: every item
  // finishes as NOT_EVALUATED (dispatch benchmarks), at once when
  // `null_delay` is none, otherwise after its delay (null_delay.h) on one of
  // the threads, with that time as its wall_seconds.
  EvaluationPool(int threads, bool null_evaluation, NullDelay null_delay = {});
  // Finishes the evaluations under way, drops queued ones, joins.
  ~EvaluationPool();
  EvaluationPool(const EvaluationPool&) = delete;
  EvaluationPool& operator=(const EvaluationPool&) = delete;

  // Queues an item, to be evaluated under `config` (not null). Its genome
  // is validated on the pool thread; an invalid one finishes as
  // INVALID_GENOME with the reason.
  void Submit(v1::WorkItem item, std::shared_ptr<const ModelConfig> config);

  // Results finished since the last call, in finishing order.
  std::vector<v1::WorkResult> TakeFinished();

  // Removes the queued items no thread has started and returns their
  // individuals (handed back on shutdown or a new session).
  std::vector<uint64_t> Abandon();

  // Items queued or being evaluated.
  int in_flight() const;

  // Readable (a counter) whenever results are waiting; TakeFinished resets
  // it. For zmq_poll.
  int wakeup_fd() const { return wakeup_fd_; }

 private:
  void Loop();
  void Finish(v1::WorkResult result, bool was_running);

  const bool null_evaluation_;
  const NullDelay null_delay_;
  int wakeup_fd_ = -1;
  mutable std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<std::pair<v1::WorkItem, std::shared_ptr<const ModelConfig>>>
      queue_;
  std::vector<v1::WorkResult> finished_;
  int running_ = 0;
  bool stopping_ = false;
  std::vector<std::thread> threads_;
};

}  // namespace animat

#endif  // ANIMAT_WORKER_EVALUATION_POOL_H_
