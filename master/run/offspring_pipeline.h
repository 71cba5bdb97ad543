// The offspring of one generation, made on a thread of their own while the
// run loop writes them to the store: each is a pure function of the run's
// seed, its id and the ranked generation before it
// (master/evolution/operators.h), made in id order and handed to the loop
// in batches as they are finished. The loop decides what happens between
// batches (writing them, serving workers); the pipeline calls nothing.
//
// Thread safety: the object is used by one thread (the loop's); its own
// thread only makes offspring into slots the loop does not read until
// they are handed.
#ifndef ANIMAT_MASTER_RUN_OFFSPRING_PIPELINE_H_
#define ANIMAT_MASTER_RUN_OFFSPRING_PIPELINE_H_

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "common/genome/genome.h"
#include "master/evolution/evolution_params.h"
#include "master/evolution/operators.h"
#include "master/lineage/store.h"

namespace animat {

// Genomes of a generation's members by id, ids increasing.
struct GenomesById {
  std::vector<uint64_t> ids;
  std::vector<Genome> genomes;
  // Each genome's evaluation key (OffspringPipeline::KeyFunction; nullopt:
  // it has none), as genomes; empty when the keys were not made.
  std::vector<std::optional<std::string>> keys;
  // The index of `id` in ids, or nullopt when it is not a member.
  std::optional<size_t> IndexOf(uint64_t id) const;
  // The genome of `id`, or null when it is not a member.
  const Genome* Find(uint64_t id) const;
};

class OffspringPipeline {
 public:
  // What an offspring's evaluation reads of its genome
  // (EvaluationKey, common/evaluation/evaluator.h); called on the
  // pipeline's thread, so it must be thread-safe.
  using KeyFunction =
      std::function<std::optional<std::string>(const Genome& genome)>;

  // Starts making the `count` offspring of `generation`, ids first,
  // first + 1, ...: `ranked` is the generation before, best first, and
  // `parents` holds its members' genomes (it must outlive the pipeline).
  // With `key`, each offspring's key is made with it (KeyOf).
  OffspringPipeline(int generation, uint64_t first, size_t count,
                    std::vector<Scored> ranked, const GenomesById* parents,
                    EvolutionParams params, KeyFunction key = nullptr);
  // Stops making offspring (those not made are abandoned) and joins.
  ~OffspringPipeline();
  OffspringPipeline(const OffspringPipeline&) = delete;
  OffspringPipeline& operator=(const OffspringPipeline&) = delete;

  // The next offspring, at most `max` (>= 1), in id order, waiting until
  // one is made; empty once all `count` have been handed.
  std::vector<lineage::NewIndividual> Next(size_t max);
  // Once all have been handed: their genomes, in id order (moved out).
  std::vector<Genome> TakeGenomes();
  // Once all have been handed: their keys (KeyOf), in id order (moved out);
  // empty without a key function.
  std::vector<std::optional<std::string>> TakeKeys();
  // The key of offspring `id`, once handed by Next; nullopt without a key
  // function, or when it gave none.
  const std::optional<std::string>& KeyOf(uint64_t id) const;

 private:
  void Make();

  const int generation_;
  const uint64_t first_;
  const std::vector<Scored> ranked_;
  const GenomesById* const parents_;
  const EvolutionParams params_;
  const KeyFunction key_;
  // Slot i is offspring first_ + i; written by the maker thread before it
  // publishes `made_` > i, read by the loop only after.
  std::vector<lineage::NewIndividual> children_;
  std::vector<Genome> genomes_;
  std::vector<std::optional<std::string>> keys_;  // As children_.
  std::atomic<size_t> made_{0};
  std::atomic<bool> abandon_{false};
  size_t handed_ = 0;  // The loop's.
  std::thread maker_;  // Last: starts once the rest is ready.
};

}  // namespace animat

#endif  // ANIMAT_MASTER_RUN_OFFSPRING_PIPELINE_H_
