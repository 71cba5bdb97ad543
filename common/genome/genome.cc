#include "common/genome/genome.h"

#include <cmath>
#include <string>

namespace animat {

const char* ElementTypeName(ElementType type) {
  switch (type) {
    case ElementType::kP:
      return "P";
    case ElementType::kGInternal:
      return "G_INTERNAL";
    case ElementType::kGMorphogen:
      return "G_MORPHOGEN";
    case ElementType::kSIn:
      return "S_IN";
    case ElementType::kSOut:
      return "S_OUT";
  }
  return "?";
}

const char* InputChannelName(int channel) {
  static const char* const kNames[kInputChannels] = {
      "MATERNAL_0", "MATERNAL_1", "MATERNAL_2", "UNIFORM", "CHEMICAL"};
  return channel >= 0 && channel < kInputChannels ? kNames[channel] : "?";
}

const char* OutputChannelName(int channel) {
  static const char* const kNames[kOutputChannels] = {
      "DIVIDE", "ROTATE_LEFT", "ROTATE_RIGHT", "SIZE", "EXPAND", "CONTRACT"};
  return channel >= 0 && channel < kOutputChannels ? kNames[channel] : "?";
}

Status ValidateGenome(const Genome& genome) {
  if (genome.elements.size() > kMaxGenomeElements) {
    return Status::InvalidArgument(
        "elements: " + std::to_string(genome.elements.size()) +
        " elements, more than the limit of " +
        std::to_string(kMaxGenomeElements));
  }
  for (size_t i = 0; i < genome.elements.size(); ++i) {
    const Element& e = genome.elements[i];
    const std::string where = "elements[" + std::to_string(i) + "]";
    if (e.sign != 1 && e.sign != -1) {
      return Status::InvalidArgument(where + ".sign: must be +1 or -1, got " +
                                     std::to_string(e.sign));
    }
    if (!std::isfinite(e.x)) {
      return Status::InvalidArgument(where + ".x: must be finite");
    }
    if (!std::isfinite(e.y)) {
      return Status::InvalidArgument(where + ".y: must be finite");
    }
    switch (e.type) {
      case ElementType::kP:
      case ElementType::kGInternal:
      case ElementType::kGMorphogen:
        if (e.channel != -1) {
          return Status::InvalidArgument(where + ".channel: a " +
                                         ElementTypeName(e.type) +
                                         " element has no channel");
        }
        break;
      case ElementType::kSIn:
        if (e.channel < 0 || e.channel >= kInputChannels) {
          return Status::InvalidArgument(
              where +
              ".channel: an S_IN element needs an input channel "
              "(MATERNAL_0, MATERNAL_1, MATERNAL_2, UNIFORM or CHEMICAL)");
        }
        break;
      case ElementType::kSOut:
        if (e.channel < 0 || e.channel >= kOutputChannels) {
          return Status::InvalidArgument(
              where +
              ".channel: an S_OUT element needs an output channel "
              "(DIVIDE, ROTATE_LEFT, ROTATE_RIGHT, SIZE, EXPAND or "
              "CONTRACT)");
        }
        break;
      default:
        return Status::InvalidArgument(where + ".type: unknown type");
    }
  }
  return Status::Ok();
}

}  // namespace animat
