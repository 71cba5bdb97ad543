#include "worker/evaluation_pool.h"

#include <sys/eventfd.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <thread>

#include "common/evaluation/evaluator.h"
#include "common/genome/genome_proto.h"
#include "common/kernels/isa.h"
#include "common/protocol/protocol.h"

namespace animat {

namespace {

v1::WorkResult::Isa IsaToProto(Isa isa) {
  switch (isa) {
    case Isa::kBaseline:
      return v1::WorkResult::BASELINE;
    case Isa::kAvx2:
      return v1::WorkResult::AVX2;
    case Isa::kAvx512:
      return v1::WorkResult::AVX512;
  }
  return v1::WorkResult::ISA_UNSPECIFIED;
}

}  // namespace

v1::WorkResult EvaluateItem(const v1::WorkItem& item,
                            const ModelConfig& config) {
  v1::WorkResult out;
  out.set_individual(item.individual());
  out.set_genome_hash(item.genome_hash());
  const auto start = std::chrono::steady_clock::now();
  Result<Genome> genome = GenomeFromProto(item.genome());
  EvaluationResult result;
  if (genome.ok()) {
    result = Evaluate(*genome, config);
  } else {
    result.status = EvalStatus::kInvalidGenome;
    result.reason = genome.status().message();
  }
  const std::chrono::duration<double> took =
      std::chrono::steady_clock::now() - start;
  if (result.reason.size() > protocol::kMaxReasonBytes) {
    // The master takes no longer reason (cut on a character's start).
    size_t cut = protocol::kMaxReasonBytes;
    while (cut > 0 &&
           (static_cast<unsigned char>(result.reason[cut]) & 0xc0) == 0x80) {
      --cut;
    }
    result.reason.resize(cut);
  }
  *out.mutable_result() = EvaluationResultToProto(result);
  out.set_wall_seconds(took.count());
  out.set_isa(IsaToProto(ActiveIsa()));
  return out;
}

namespace {

v1::WorkResult NotEvaluated(const v1::WorkItem& item, double wall_seconds) {
  v1::WorkResult out;
  out.set_individual(item.individual());
  out.set_genome_hash(item.genome_hash());
  out.mutable_result()->set_status(v1::EvaluationResult::NOT_EVALUATED);
  out.mutable_result()->set_reason("null-evaluation worker");
  out.set_wall_seconds(wall_seconds);
  return out;
}

// A null evaluation that takes its item's delay: slept on the calling
// thread, its measured length the result's wall time.
v1::WorkResult DelayedNotEvaluated(const v1::WorkItem& item,
                                   const NullDelay& delay) {
  const auto start = std::chrono::steady_clock::now();
  std::this_thread::sleep_for(std::chrono::duration<double>(
      NullDelaySeconds(delay, item.genome_hash())));
  const std::chrono::duration<double> took =
      std::chrono::steady_clock::now() - start;
  return NotEvaluated(item, took.count());
}

}  // namespace

EvaluationPool::EvaluationPool(int threads, bool null_evaluation,
                               NullDelay null_delay)
    : null_evaluation_(null_evaluation), null_delay_(null_delay) {
  wakeup_fd_ = eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
  if (!null_evaluation_ || !null_delay_.none()) {
    for (int i = 0; i < threads; ++i) threads_.emplace_back([this] { Loop(); });
  }
}

EvaluationPool::~EvaluationPool() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
    queue_.clear();
  }
  ready_.notify_all();
  for (std::thread& t : threads_) t.join();
  if (wakeup_fd_ >= 0) close(wakeup_fd_);
}

void EvaluationPool::Submit(v1::WorkItem item,
                            std::shared_ptr<const ModelConfig> config) {
  if (null_evaluation_ && null_delay_.none()) {
    Finish(NotEvaluated(item, 0), /*was_running=*/false);
    return;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    queue_.emplace_back(std::move(item), std::move(config));
  }
  ready_.notify_one();
}

void EvaluationPool::Loop() {
  for (;;) {
    v1::WorkItem item;
    std::shared_ptr<const ModelConfig> config;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      ready_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      if (stopping_) return;
      item = std::move(queue_.front().first);
      config = std::move(queue_.front().second);
      queue_.pop_front();
      ++running_;
    }
    Finish(null_evaluation_ ? DelayedNotEvaluated(item, null_delay_)
                            : EvaluateItem(item, *config),
           /*was_running=*/true);
  }
}

void EvaluationPool::Finish(v1::WorkResult result, bool was_running) {
  {
    // One step, so in_flight() never misses an item between the two.
    std::lock_guard<std::mutex> lock(mutex_);
    if (was_running) --running_;
    finished_.push_back(std::move(result));
  }
  const uint64_t one = 1;
  // A full counter (never in practice) only means the fd stays readable.
  [[maybe_unused]] const ssize_t written = write(wakeup_fd_, &one, sizeof(one));
}

std::vector<v1::WorkResult> EvaluationPool::TakeFinished() {
  uint64_t count;
  [[maybe_unused]] const ssize_t read_bytes =
      read(wakeup_fd_, &count, sizeof(count));
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<v1::WorkResult> out;
  out.swap(finished_);
  return out;
}

std::vector<uint64_t> EvaluationPool::Abandon() {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<uint64_t> ids;
  for (const auto& [item, config] : queue_) ids.push_back(item.individual());
  queue_.clear();
  return ids;
}

int EvaluationPool::in_flight() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return static_cast<int>(queue_.size()) + running_;
}

}  // namespace animat
