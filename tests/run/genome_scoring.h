// A stand-in for the workers in the run loop's tests: an evaluation
// service whose result is a pure function of what a simulation reads of
// the genome, as a simulation's is, returned at once; so that whole evolutions
// run in a fraction of a second and can be compared individual by individual.
// The real workers' determinism is tested in tests/master/.
//
// Not thread-safe, like the services it stands for.
#ifndef ANIMAT_TESTS_RUN_GENOME_SCORING_H_
#define ANIMAT_TESTS_RUN_GENOME_SCORING_H_

#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "common/base/clock.h"
#include "common/evaluation/evaluator.h"
#include "common/genome/genome_proto.h"
#include "common/protocol/genome_wire.h"
#include "master/dispatch/evaluation_service.h"

namespace animat::testing {

// Evaluates each genome at once, its result a function of what a
// simulation reads of it alone (EvaluationKey; the bytes for an invalid
// genome), through a hash: one in 7 non-viable, one in 11 crashed (a status
// that says nothing about the genome), the rest ok with a fitness in
// [0, 1).
class GenomeScoring final : public EvaluationService {
 public:
  explicit GenomeScoring(bool follow_genome) : follow_genome_(follow_genome) {}

  void Submit(uint64_t individual, const v1::Genome& genome) override {
    Submit(individual, protocol::SerializeGenome(genome));
  }
  void Submit(uint64_t individual,
              const protocol::SerializedGenome& genome) override {
    queue_.emplace_back(individual, KeyHash(genome));
    submitted_.insert(individual);
  }
  std::vector<Completion> Poll(int) override {
    std::vector<Completion> done;
    for (const auto& [id, h] : queue_) {
      Completion c;
      c.individual = id;
      c.worker = "stand-in:1";
      c.wall_seconds = 0.5;
      c.isa = "avx2";
      v1::EvaluationResult& r = c.result;
      if (h % 7 == 0) {
        r.set_status(v1::EvaluationResult::NON_VIABLE);
        r.set_reason("no path");
      } else if (h % 11 == 0) {
        r.set_status(v1::EvaluationResult::CRASHED);
        r.set_reason("signal 11");
      } else {
        r.set_status(v1::EvaluationResult::OK);
        r.set_fitness(static_cast<double>(h >> 11) * 0x1p-53);
        r.set_distance(r.fitness());
        r.set_max_overlap(0.0);
      }
      r.set_cells(static_cast<int>(h % 32));
      r.set_steps(100);
      r.set_state_hash(h);
      done.push_back(std::move(c));
    }
    queue_.clear();
    return done;
  }
  void Acknowledge(const std::vector<uint64_t>&) override {}
  size_t pending() const override { return queue_.size(); }
  const Clock& clock() const override { return RealClock(); }
  bool results_follow_genome() const override { return follow_genome_; }

  const std::set<uint64_t>& submitted() const { return submitted_; }

 private:
  // FNV-1a of what an evaluation reads of the genome (EvaluationKey under
  // the default model), or the bytes' hash for an invalid genome: genomes
  // that a simulation cannot tell apart score alike, as they would.
  static uint64_t KeyHash(const protocol::SerializedGenome& genome) {
    v1::Genome message;
    if (!message.ParseFromString(genome.bytes)) return genome.hash;
    Result<Genome> parsed = GenomeFromProto(message);
    if (!parsed.ok()) return genome.hash;
    const std::optional<std::string> key =
        EvaluationKey(*parsed, ModelConfig{});
    if (!key) return genome.hash;
    uint64_t h = 0xcbf29ce484222325ULL;
    for (unsigned char c : *key) h = (h ^ c) * 0x100000001b3ULL;
    return h;
  }

  bool follow_genome_;
  // Individuals submitted, with their KeyHash.
  std::vector<std::pair<uint64_t, uint64_t>> queue_;
  std::set<uint64_t> submitted_;
};

}  // namespace animat::testing

#endif  // ANIMAT_TESTS_RUN_GENOME_SCORING_H_
