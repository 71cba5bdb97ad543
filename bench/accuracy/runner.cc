#include "bench/accuracy/runner.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <ctime>
#include <limits>

#include "common/physics/soft_body.h"

namespace animat::accuracy {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Records the centre of mass during motion.
class ComRecorder : public EvaluationObserver {
 public:
  ComRecorder(int motion_steps, Run* run)
      : motion_steps_(motion_steps), run_(run) {}

  void OnMotionStep(MotionPhase phase, int step, const MotionState& state,
                    std::span<const double> expand,
                    std::span<const double> contract) override {
    (void)expand;
    (void)contract;
    if (phase != MotionPhase::kMotion) return;
    if (step % kSampleInterval != 0 && step != motion_steps_) return;
    const Vec2 com = CentreOfMass(state);
    if (step == 0) start_ = com;
    run_->sample_step.push_back(step);
    run_->displacement.push_back(com - start_);
  }

 private:
  int motion_steps_;
  Run* run_;
  Vec2 start_;
};

// CPU time used by the calling thread, in seconds.
double ThreadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

int SampleIndex(const Run& run, int step) {
  const auto it =
      std::lower_bound(run.sample_step.begin(), run.sample_step.end(), step);
  if (it == run.sample_step.end() || *it != step) return -1;
  return static_cast<int>(it - run.sample_step.begin());
}

}  // namespace

bool Run::SameBits(const Run& other) const {
  return status == other.status && state_hash == other.state_hash &&
         std::bit_cast<uint64_t>(fitness) ==
             std::bit_cast<uint64_t>(other.fitness);
}

Run RunEvaluation(const Genome& genome, const ModelConfig& config) {
  Run run;
  ComRecorder recorder(config.evaluation.motion_steps, &run);
  const double cpu_start = ThreadCpuSeconds();
  const auto start = std::chrono::steady_clock::now();
  EvaluationResult result = Evaluate(genome, config, &recorder);
  const auto end = std::chrono::steady_clock::now();
  run.cpu_seconds = ThreadCpuSeconds() - cpu_start;
  run.seconds = std::chrono::duration<double>(end - start).count();
  run.status = result.status;
  run.reason = std::move(result.reason);
  run.fitness = result.fitness.value_or(0.0);
  run.max_overlap = result.max_overlap.value_or(0.0);
  run.state_hash = result.state_hash;
  return run;
}

double FitnessError(const Run& run, const Run& reference) {
  if (!run.ok() || !reference.ok() || !(reference.fitness > 0.0)) {
    return kInfinity;
  }
  return std::abs(run.fitness - reference.fitness) / reference.fitness;
}

double TrajectoryError(const Run& run, const Run& reference) {
  if (!run.ok() || !reference.ok() || !(reference.fitness > 0.0) ||
      run.sample_step != reference.sample_step) {
    return kInfinity;
  }
  double worst = 0.0;
  for (size_t i = 0; i < run.displacement.size(); ++i) {
    worst = std::max(worst,
                     Length(run.displacement[i] - reference.displacement[i]));
  }
  return worst / reference.fitness;
}

double Divergence(const Run& a, const Run& b, int step, double scale) {
  if (!a.ok() || !b.ok() || !(scale > 0.0)) return kInfinity;
  const int i = SampleIndex(a, step);
  const int j = SampleIndex(b, step);
  if (i < 0 || j < 0) return kInfinity;
  return Length(a.displacement[i] - b.displacement[j]) / scale;
}

}  // namespace animat::accuracy
