// Counter-based random streams (Philox4x32-10, Salmon et al., SC'11).
//
// Every random draw of the project comes from a RandomStream keyed by
// (run seed, individual, purpose): the n-th draw of a stream is a pure
// function of those three numbers and n, so results do not depend on which
// worker draws, in which order, or after how many restarts. Streams are
// cheap value objects (a few words); one stream must not be shared between
// threads without external locking, but any number of streams with the
// same key may be created anywhere and give the same sequence.
#ifndef ANIMAT_COMMON_BASE_RNG_H_
#define ANIMAT_COMMON_BASE_RNG_H_

#include <array>
#include <cstdint>

namespace animat {

// What a stream is for. The numbers are part of the determinism contract
// (a stored run replays only if they stay): never renumber, only append.
enum class StreamPurpose : uint32_t {
  kRandomGenome = 1,  // Initial genomes (docs/model.md §9.3).
  kSelection = 2,     // Tournaments choosing an offspring's parents.
  kVariation = 3,     // Whether an offspring is made by crossover.
  kCrossover = 4,     // Crossover points.
  kMutation = 5,      // Mutations of an offspring's genome.
  kNullFitness = 6,   // Stand-in fitness of null evaluations (benchmarks).
  kNullDelay = 7,     // Delays of null evaluations (benchmarks).
};

// One Philox4x32-10 block: 4 output words for a 128-bit counter and a
// 64-bit key. Exposed for known-answer tests.
std::array<uint32_t, 4> Philox4x32(std::array<uint32_t, 4> counter,
                                   std::array<uint32_t, 2> key);

class RandomStream {
 public:
  RandomStream(uint64_t seed, uint64_t individual, StreamPurpose purpose);

  // The next 64 uniformly distributed bits.
  uint64_t NextU64();
  // Uniform in [0, 1) with 53 random bits.
  double NextDouble();
  // Uniform in [lo, hi) (lo when lo == hi).
  double Uniform(double lo, double hi);
  // Uniform integer in [0, n), without modulo bias. Precondition: n > 0.
  uint64_t Below(uint64_t n);
  // Fair coin.
  bool NextBool() { return (NextU64() >> 63) != 0; }

  // Number of 64-bit draws made so far.
  uint64_t draws() const { return draws_; }

 private:
  std::array<uint32_t, 2> key_;
  uint64_t individual_;
  uint32_t purpose_;
  uint64_t draws_ = 0;
};

}  // namespace animat

#endif  // ANIMAT_COMMON_BASE_RNG_H_
