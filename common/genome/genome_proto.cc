#include "common/genome/genome_proto.h"

#include <string>

namespace animat {
namespace {

constexpr int kFirstInput = v1::Element::MATERNAL_0;
constexpr int kFirstOutput = v1::Element::DIVIDE;

// The InputChannel of a proto channel, -1 when it is not an input: the
// paper's four are numbered before the outputs, CHEMICAL after them.
int InputFromProto(int channel) {
  if (channel >= kFirstInput && channel < kFirstOutput) {
    return channel - kFirstInput;
  }
  if (channel == v1::Element::CHEMICAL) {
    return static_cast<int>(InputChannel::kChemical);
  }
  return -1;
}

}  // namespace

v1::Element::Channel InputChannelToProto(int channel) {
  if (channel == static_cast<int>(InputChannel::kChemical)) {
    return v1::Element::CHEMICAL;
  }
  return static_cast<v1::Element::Channel>(kFirstInput + channel);
}

v1::Element::Channel OutputChannelToProto(int channel) {
  return static_cast<v1::Element::Channel>(kFirstOutput + channel);
}

Result<Genome> GenomeFromProto(const v1::Genome& message) {
  if (static_cast<size_t>(message.elements_size()) > kMaxGenomeElements) {
    return Status::InvalidArgument(
        "elements: " + std::to_string(message.elements_size()) +
        " elements, more than the limit of " +
        std::to_string(kMaxGenomeElements));
  }
  Genome genome;
  genome.elements.reserve(message.elements_size());
  for (int i = 0; i < message.elements_size(); ++i) {
    const v1::Element& m = message.elements(i);
    const std::string where = "elements[" + std::to_string(i) + "]";
    Element e;
    switch (m.type()) {
      case v1::Element::P:
        e.type = ElementType::kP;
        break;
      case v1::Element::G_INTERNAL:
        e.type = ElementType::kGInternal;
        break;
      case v1::Element::G_MORPHOGEN:
        e.type = ElementType::kGMorphogen;
        break;
      case v1::Element::S_IN:
        e.type = ElementType::kSIn;
        break;
      case v1::Element::S_OUT:
        e.type = ElementType::kSOut;
        break;
      default:
        return Status::InvalidArgument(
            where +
            ".type: must be one of P, G_INTERNAL, G_MORPHOGEN, S_IN, "
            "S_OUT, got " +
            std::to_string(m.type()));
    }
    e.sign = m.sign();
    e.x = m.x();
    e.y = m.y();
    const int channel = m.channel();
    const std::string got = v1::Element::Channel_IsValid(channel)
                                ? v1::Element::Channel_Name(m.channel())
                                : std::to_string(channel);
    if (e.type == ElementType::kSIn) {
      e.channel = InputFromProto(channel);
      if (e.channel < 0) {
        return Status::InvalidArgument(
            where +
            ".channel: an S_IN element needs an input channel "
            "(MATERNAL_0, MATERNAL_1, MATERNAL_2, UNIFORM or CHEMICAL), got " +
            got);
      }
    } else if (e.type == ElementType::kSOut) {
      if (channel < kFirstOutput || channel >= kFirstOutput + kOutputChannels) {
        return Status::InvalidArgument(
            where +
            ".channel: an S_OUT element needs an output channel "
            "(DIVIDE, ROTATE_LEFT, ROTATE_RIGHT, SIZE, EXPAND or "
            "CONTRACT), got " +
            got);
      }
      e.channel = channel - kFirstOutput;
    } else if (channel != v1::Element::CHANNEL_NONE) {
      return Status::InvalidArgument(where + ".channel: a " +
                                     ElementTypeName(e.type) +
                                     " element has no channel, got " + got);
    }
    genome.elements.push_back(e);
  }
  Status status = ValidateGenome(genome);
  if (!status.ok()) return status;
  return genome;
}

v1::Genome GenomeToProto(const Genome& genome) {
  v1::Genome message;
  for (const Element& e : genome.elements) {
    v1::Element* m = message.add_elements();
    switch (e.type) {
      case ElementType::kP:
        m->set_type(v1::Element::P);
        break;
      case ElementType::kGInternal:
        m->set_type(v1::Element::G_INTERNAL);
        break;
      case ElementType::kGMorphogen:
        m->set_type(v1::Element::G_MORPHOGEN);
        break;
      case ElementType::kSIn:
        m->set_type(v1::Element::S_IN);
        m->set_channel(InputChannelToProto(e.channel));
        break;
      case ElementType::kSOut:
        m->set_type(v1::Element::S_OUT);
        m->set_channel(OutputChannelToProto(e.channel));
        break;
    }
    m->set_sign(e.sign);
    m->set_x(e.x);
    m->set_y(e.y);
  }
  return message;
}

}  // namespace animat
