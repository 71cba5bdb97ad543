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

Genome RandomGenome(RandomStream& stream, int units, double coordinate_max) {
  // Tokens: -1 - k for S element k (inputs, then outputs), u >= 0 for unit u.
  std::vector<int> order;
  for (int u = 0; u < units; ++u) order.push_back(u);
  for (int k = 0; k < kInputChannels + kOutputChannels; ++k) {
    order.push_back(-1 - k);
  }
  // Fisher-Yates shuffle.
  for (size_t i = order.size(); i > 1; --i) {
    const size_t j = static_cast<size_t>(stream.Below(i));
    std::swap(order[i - 1], order[j]);
  }
  Genome genome;
  for (int token : order) {
    if (token >= 0) {
      genome.elements.push_back(
          RandomElement(stream, ElementType::kP, -1, coordinate_max));
      const ElementType g = stream.NextBool() ? ElementType::kGMorphogen
                                              : ElementType::kGInternal;
      genome.elements.push_back(RandomElement(stream, g, -1, coordinate_max));
    } else {
      const int k = -1 - token;
      if (k < kInputChannels) {
        genome.elements.push_back(
            RandomElement(stream, ElementType::kSIn, k, coordinate_max));
      } else {
        genome.elements.push_back(RandomElement(
            stream, ElementType::kSOut, k - kInputChannels, coordinate_max));
      }
    }
  }
  return genome;
}

}  // namespace animat
