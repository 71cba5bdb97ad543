#include "common/genome/random_genome.h"

#include <utility>

namespace animat {
namespace {

Element RandomElement(RandomStream& stream, ElementType type, int channel,
                      double coordinate_max) {
  Element e;
  e.type = type;
  e.channel = channel;
  e.sign = stream.NextBool() ? 1 : -1;
  e.x = stream.Uniform(0.0, coordinate_max);
  e.y = stream.Uniform(0.0, coordinate_max);
  return e;
}

}  // namespace

Genome RandomGenome(RandomStream& stream, int units, double coordinate_max,
                    bool chemical) {
  // Tokens: -1 - k for S element k (inputs, then outputs), u >= 0 for unit u.
  std::vector<int> order;
  for (int u = 0; u < units; ++u) order.push_back(u);
  for (int k = 0; k < kPaperInputChannels + kOutputChannels; ++k) {
    order.push_back(-1 - k);
  }
  // Fisher-Yates shuffle.
  for (size_t i = order.size(); i > 1; --i) {
    const size_t j = static_cast<size_t>(stream.Below(i));
    std::swap(order[i - 1], order[j]);
  }
  Genome genome;
  // Where each token's elements start, then the end: the boundaries a
  // CHEMICAL element may be inserted at without splitting a unit.
  std::vector<size_t> boundaries;
  for (int token : order) {
    boundaries.push_back(genome.elements.size());
    if (token >= 0) {
      genome.elements.push_back(
          RandomElement(stream, ElementType::kP, -1, coordinate_max));
      const ElementType g = stream.NextBool() ? ElementType::kGMorphogen
                                              : ElementType::kGInternal;
      genome.elements.push_back(RandomElement(stream, g, -1, coordinate_max));
    } else {
      const int k = -1 - token;
      if (k < kPaperInputChannels) {
        genome.elements.push_back(
            RandomElement(stream, ElementType::kSIn, k, coordinate_max));
      } else {
        genome.elements.push_back(RandomElement(stream, ElementType::kSOut,
                                                k - kPaperInputChannels,
                                                coordinate_max));
      }
    }
  }
  boundaries.push_back(genome.elements.size());
  if (chemical) {
    const size_t at = boundaries[stream.Below(boundaries.size())];
    const Element e = RandomElement(stream, ElementType::kSIn,
                                    static_cast<int>(InputChannel::kChemical),
                                    coordinate_max);
    genome.elements.insert(genome.elements.begin() + static_cast<ptrdiff_t>(at),
                           e);
  }
  return genome;
}

}  // namespace animat
