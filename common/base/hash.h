// A 64-bit FNV-1a hash for fingerprints of simulation states, genomes and
// configurations.
//
// Used for golden-determinism checks and fingerprints, never for hash
// tables or security. Hashes the exact bit patterns of doubles, so two states
// hash equal only if every bit agrees (+0.0 and -0.0 differ). Not thread-safe
// per object; cheap to copy.
#ifndef ANIMAT_COMMON_BASE_HASH_H_
#define ANIMAT_COMMON_BASE_HASH_H_

#include <bit>
#include <cstdint>
#include <span>
#include <string_view>

namespace animat {

class StateHash {
 public:
  void AddU64(uint64_t v) {
    for (int i = 0; i < 8; ++i) {
      hash_ ^= (v >> (8 * i)) & 0xFFu;
      hash_ *= 0x100000001B3ull;
    }
  }
  void AddDouble(double v) { AddU64(std::bit_cast<uint64_t>(v)); }
  void AddBytes(std::string_view bytes) {
    for (unsigned char c : bytes) {
      hash_ ^= c;
      hash_ *= 0x100000001B3ull;
    }
  }
  void AddDoubles(std::span<const double> values) {
    for (double v : values) AddDouble(v);
  }
  uint64_t value() const { return hash_; }

 private:
  uint64_t hash_ = 0xCBF29CE484222325ull;
};

}  // namespace animat

#endif  // ANIMAT_COMMON_BASE_HASH_H_
