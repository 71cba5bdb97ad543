// The genome: an ordered list of elements (docs/model.md §1).
//
// Plain value types. A Genome made by GenomeFromProto or RandomGenome is
// valid (see ValidateGenome); code that builds one by hand should validate
// it before use.
#ifndef ANIMAT_COMMON_GENOME_GENOME_H_
#define ANIMAT_COMMON_GENOME_GENOME_H_

#include <cstddef>
#include <cstdint>
#include <vector>

#include "common/base/status.h"

namespace animat {

enum class ElementType : uint8_t {
  kP,           // Regulatory region.
  kGInternal,   // Factor that stays in its cell.
  kGMorphogen,  // Factor that also diffuses to other cells.
  kSIn,         // Input node.
  kSOut,        // Output node.
};

// Input channels: three maternal morphogens and a uniform 1 [paper], and
// the chemical of active guidance, sensed by skin cells during motion
// (docs/model.md §10.2) [ours, v2].
enum class InputChannel : uint8_t {
  kMaternal0,
  kMaternal1,
  kMaternal2,
  kUniform,
  kChemical,
};
inline constexpr int kInputChannels = 5;
// The paper's channels, the first four: random genomes and mutations draw
// among these alone unless the run asks for guidance, so paper runs draw
// exactly as before the chemical channel existed.
inline constexpr int kPaperInputChannels = 4;

// Output channels [paper].
enum class OutputChannel : uint8_t {
  kDivide,
  kRotateLeft,
  kRotateRight,
  kSize,
  kExpand,
  kContract,
};
inline constexpr int kOutputChannels = 6;
// Every output channel, in the enum's order.
inline constexpr OutputChannel kAllOutputChannels[kOutputChannels] = {
    OutputChannel::kDivide,      OutputChannel::kRotateLeft,
    OutputChannel::kRotateRight, OutputChannel::kSize,
    OutputChannel::kExpand,      OutputChannel::kContract};

// Genomes longer than this are rejected (bounds the network's cost).
inline constexpr size_t kMaxGenomeElements = 10000;

struct Element {
  ElementType type = ElementType::kP;
  int sign = 1;    // +1 or -1.
  double x = 0.0;  // Affinity-plane coordinates, finite.
  double y = 0.0;
  // For kSIn an InputChannel, for kSOut an OutputChannel, else -1.
  int channel = -1;

  bool IsG() const {
    return type == ElementType::kGInternal || type == ElementType::kGMorphogen;
  }
  bool operator==(const Element&) const = default;
};

struct Genome {
  std::vector<Element> elements;
  bool operator==(const Genome&) const = default;
};

// Checks size, signs, finite coordinates and channels. The message names
// the element: "elements[3].sign: must be +1 or -1, got 0".
Status ValidateGenome(const Genome& genome);

const char* ElementTypeName(ElementType type);  // "P", "S_OUT", ...
const char* InputChannelName(int channel);      // "MATERNAL_0", ...
const char* OutputChannelName(int channel);     // "DIVIDE", ...

}  // namespace animat

#endif  // ANIMAT_COMMON_GENOME_GENOME_H_
