#include "master/run/offspring_pipeline.h"

#include <algorithm>

#include "common/protocol/genome_wire.h"

namespace animat {

std::optional<size_t> GenomesById::IndexOf(uint64_t id) const {
  const auto it = std::lower_bound(ids.begin(), ids.end(), id);
  if (it == ids.end() || *it != id) return std::nullopt;
  return static_cast<size_t>(it - ids.begin());
}

const Genome* GenomesById::Find(uint64_t id) const {
  const std::optional<size_t> index = IndexOf(id);
  return index ? &genomes[*index] : nullptr;
}

OffspringPipeline::OffspringPipeline(int generation, uint64_t first,
                                     size_t count, std::vector<Scored> ranked,
                                     const GenomesById* parents,
                                     EvolutionParams params, KeyFunction key)
    : generation_(generation),
      first_(first),
      ranked_(std::move(ranked)),
      parents_(parents),
      params_(std::move(params)),
      key_(std::move(key)),
      children_(count),
      genomes_(count),
      keys_(count),
      maker_([this] { Make(); }) {}

OffspringPipeline::~OffspringPipeline() {
  abandon_.store(true, std::memory_order_relaxed);
  maker_.join();
}

void OffspringPipeline::Make() {
  const auto genome_of = [this](uint64_t id) -> const Genome& {
    return *parents_->Find(id);
  };
  for (size_t i = 0;
       i < children_.size() && !abandon_.load(std::memory_order_relaxed); ++i) {
    const uint64_t id = first_ + i;
    Offspring offspring = MakeOffspring(id, ranked_, genome_of, params_);
    lineage::NewIndividual& n = children_[i];
    n.id = id;
    n.generation = generation_;
    n.parents = std::move(offspring.parents);
    n.operators = std::move(offspring.operators);
    n.serialized = protocol::SerializeGenome(offspring.genome);
    if (key_) keys_[i] = key_(offspring.genome);
    genomes_[i] = std::move(offspring.genome);
    made_.store(i + 1, std::memory_order_release);
    made_.notify_one();
  }
}

std::vector<lineage::NewIndividual> OffspringPipeline::Next(size_t max) {
  std::vector<lineage::NewIndividual> batch;
  if (handed_ == children_.size()) return batch;
  size_t made = made_.load(std::memory_order_acquire);
  while (made <= handed_) {
    made_.wait(made, std::memory_order_acquire);
    made = made_.load(std::memory_order_acquire);
  }
  const size_t end = std::min(made, handed_ + std::max<size_t>(max, 1));
  batch.reserve(end - handed_);
  for (; handed_ < end; ++handed_) {
    batch.push_back(std::move(children_[handed_]));
  }
  return batch;
}

std::vector<Genome> OffspringPipeline::TakeGenomes() {
  return std::move(genomes_);
}

std::vector<std::optional<std::string>> OffspringPipeline::TakeKeys() {
  if (!key_) return {};
  return std::move(keys_);
}

const std::optional<std::string>& OffspringPipeline::KeyOf(uint64_t id) const {
  return keys_.at(static_cast<size_t>(id - first_));
}

}  // namespace animat
