#include "master/campaign/shared_evaluators.h"

#include <chrono>

#include "common/protocol/genome_wire.h"

namespace animat {

namespace {
constexpr uint64_t kIdMask = (uint64_t{1} << SharedEvaluators::kIdBits) - 1;
}  // namespace

class SharedEvaluators::Lane final : public EvaluationService {
 public:
  Lane(SharedEvaluators* owner, uint64_t index, size_t config)
      : owner_(owner), index_(index), config_(config) {}

  void Submit(uint64_t individual, const v1::Genome& genome) override {
    Submit(individual, protocol::SerializeGenome(genome));
  }
  void Submit(uint64_t individual,
              const protocol::SerializedGenome& genome) override {
    std::lock_guard<std::mutex> lock(owner_->mutex_);
    if (individual > kIdMask) {
      if (error_.ok()) {
        error_ = Status::InvalidArgument(
            "individual " + std::to_string(individual) + " is beyond the " +
            std::to_string(kIdBits) + "-bit ids a campaign's run may have");
      }
      return;
    }
    if (!pending_.insert(individual).second) return;
    owner_->submitted_.push_back({config_, Key(individual), genome});
  }
  std::vector<Completion> Poll(int timeout_ms) override {
    std::unique_lock<std::mutex> lock(owner_->mutex_);
    if (timeout_ms > 0) {
      ready_.wait_for(lock, std::chrono::milliseconds(timeout_ms),
                      [this] { return !completions_.empty(); });
    }
    std::vector<Completion> done;
    done.swap(completions_);
    return done;
  }
  void Acknowledge(const std::vector<uint64_t>& individuals) override {
    std::lock_guard<std::mutex> lock(owner_->mutex_);
    for (uint64_t id : individuals) {
      if (id <= kIdMask) owner_->acknowledged_.push_back(Key(id));
    }
  }
  size_t pending() const override {
    std::lock_guard<std::mutex> lock(owner_->mutex_);
    return pending_.size();
  }
  const Clock& clock() const override { return owner_->service_->clock(); }

  // The pump's side, under the owner's mutex.
  void Deliver(Completion completion) {
    completion.individual &= kIdMask;
    if (pending_.erase(completion.individual) == 0) return;
    completions_.push_back(std::move(completion));
    ready_.notify_one();
  }
  const Status& error() const { return error_; }

 private:
  uint64_t Key(uint64_t individual) const {
    return (index_ << kIdBits) | individual;
  }

  SharedEvaluators* owner_;
  uint64_t index_;
  size_t config_;
  std::set<uint64_t> pending_;  // Submitted, not completed.
  std::vector<Completion> completions_;
  std::condition_variable ready_;
  Status error_;
};

SharedEvaluators::SharedEvaluators(MultiConfigService* service)
    : service_(service) {}

SharedEvaluators::~SharedEvaluators() = default;

EvaluationService* SharedEvaluators::AddLane(size_t config) {
  std::lock_guard<std::mutex> lock(mutex_);
  lanes_.push_back(std::make_unique<Lane>(this, lanes_.size(), config));
  return lanes_.back().get();
}

void SharedEvaluators::Pump(int timeout_ms) {
  // Slices of one millisecond of the service's polling (counted, not
  // timed: the service keeps the time).
  for (int slice = 0;; ++slice) {
    HandOver();
    std::vector<Completion> done = service_->Poll(timeout_ms > 0 ? 1 : 0);
    if (!done.empty()) {
      std::lock_guard<std::mutex> lock(mutex_);
      for (Completion& completion : done) {
        const uint64_t lane = completion.individual >> kIdBits;
        if (lane < lanes_.size()) lanes_[lane]->Deliver(std::move(completion));
      }
      return;
    }
    if (slice + 1 >= timeout_ms) return;
  }
}

void SharedEvaluators::HandOver() {
  std::deque<Submission> submitted;
  std::vector<uint64_t> acknowledged;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    submitted.swap(submitted_);
    acknowledged.swap(acknowledged_);
  }
  for (const Submission& s : submitted) {
    service_->SubmitUnder(s.config, s.key, s.genome);
  }
  if (!acknowledged.empty()) service_->Acknowledge(acknowledged);
}

Status SharedEvaluators::error(size_t index) const {
  std::lock_guard<std::mutex> lock(mutex_);
  return index < lanes_.size() ? lanes_[index]->error() : Status::Ok();
}

}  // namespace animat
