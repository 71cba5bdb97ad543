#include "common/base/rng.h"

#include <cassert>

namespace animat {
namespace {

constexpr uint32_t kMul0 = 0xD2511F53u;
constexpr uint32_t kMul1 = 0xCD9E8D57u;
constexpr uint32_t kWeyl0 = 0x9E3779B9u;
constexpr uint32_t kWeyl1 = 0xBB67AE85u;

inline void MulHiLo(uint32_t a, uint32_t b, uint32_t* hi, uint32_t* lo) {
  const uint64_t product = static_cast<uint64_t>(a) * b;
  *hi = static_cast<uint32_t>(product >> 32);
  *lo = static_cast<uint32_t>(product);
}

}  // namespace

std::array<uint32_t, 4> Philox4x32(std::array<uint32_t, 4> ctr,
                                   std::array<uint32_t, 2> key) {
  for (int round = 0; round < 10; ++round) {
    if (round > 0) {
      key[0] += kWeyl0;
      key[1] += kWeyl1;
    }
    uint32_t hi0, lo0, hi1, lo1;
    MulHiLo(kMul0, ctr[0], &hi0, &lo0);
    MulHiLo(kMul1, ctr[2], &hi1, &lo1);
    ctr = {hi1 ^ ctr[1] ^ key[0], lo1, hi0 ^ ctr[3] ^ key[1], lo0};
  }
  return ctr;
}

RandomStream::RandomStream(uint64_t seed, uint64_t individual,
                           StreamPurpose purpose)
    : key_{static_cast<uint32_t>(seed), static_cast<uint32_t>(seed >> 32)},
      individual_(individual),
      purpose_(static_cast<uint32_t>(purpose)) {}

uint64_t RandomStream::NextU64() {
  // Counter words: draw index, purpose, individual (low, high). One block
  // gives 128 bits; we use the first 64 so that draw n is block n.
  const std::array<uint32_t, 4> ctr = {
      static_cast<uint32_t>(draws_), purpose_,
      static_cast<uint32_t>(individual_),
      static_cast<uint32_t>(individual_ >> 32)};
  assert((draws_ >> 32) == 0 && "more than 2^32 draws from one stream");
  ++draws_;
  const std::array<uint32_t, 4> out = Philox4x32(ctr, key_);
  return (static_cast<uint64_t>(out[1]) << 32) | out[0];
}

double RandomStream::NextDouble() {
  return static_cast<double>(NextU64() >> 11) * 0x1.0p-53;
}

double RandomStream::Uniform(double lo, double hi) {
  return lo + (hi - lo) * NextDouble();
}

uint64_t RandomStream::Below(uint64_t n) {
  assert(n > 0);
  // Rejection sampling on the largest multiple of n below 2^64.
  const uint64_t limit = UINT64_MAX - (UINT64_MAX % n + 1) % n;
  uint64_t x;
  do {
    x = NextU64();
  } while (x > limit);
  return x % n;
}

}  // namespace animat
