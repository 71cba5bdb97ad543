// protocol::SerializeGenome(const Genome&): animat.v1.Genome's wire bytes
// written straight from a Genome, byte for byte what protobuf writes for
// GenomeToProto(genome) (tests/dispatch/genome_encoder_test.cc compares
// them): fields in field order, proto3 defaults (0, and doubles whose bits
// are all 0) left out, negative int32 and enum values as 10-byte varints.
// The tags, varints and fixed64s are protobuf's own CodedOutputStream
// writers, into a buffer sized for the worst case.
#include <cstring>

#include <google/protobuf/io/coded_stream.h>

#include "common/base/hash.h"
#include "common/genome/genome_proto.h"
#include "common/protocol/genome_wire.h"

namespace animat::protocol {
namespace {

using google::protobuf::io::CodedOutputStream;

// Wire types.
constexpr uint32_t kVarint = 0;
constexpr uint32_t kFixed64 = 1;
constexpr uint32_t kLengthDelimited = 2;

constexpr uint32_t Tag(uint32_t field, uint32_t wire_type) {
  return field << 3 | wire_type;
}

// animat.v1.Element's fields.
constexpr uint32_t kTypeTag = Tag(1, kVarint);
constexpr uint32_t kSignTag = Tag(2, kVarint);
constexpr uint32_t kXTag = Tag(3, kFixed64);
constexpr uint32_t kYTag = Tag(4, kFixed64);
constexpr uint32_t kChannelTag = Tag(5, kVarint);
// animat.v1.Genome.elements.
constexpr uint32_t kElementsTag = Tag(1, kLengthDelimited);

uint64_t Bits(double value) {
  uint64_t bits;
  std::memcpy(&bits, &value, sizeof(bits));
  return bits;
}

// The wire values of one element, as GenomeToProto sets them.
struct ElementFields {
  int32_t type;
  int32_t sign;
  uint64_t x, y;  // Bits.
  int32_t channel;
};

ElementFields Fields(const Element& e) {
  ElementFields f;
  f.type = static_cast<int32_t>(e.type) + v1::Element::P;
  f.sign = e.sign;
  f.x = Bits(e.x);
  f.y = Bits(e.y);
  f.channel = v1::Element::CHANNEL_NONE;
  // The channel numbers of GenomeToProto (CHEMICAL is not after UNIFORM).
  if (e.type == ElementType::kSIn) f.channel = InputChannelToProto(e.channel);
  if (e.type == ElementType::kSOut) {
    f.channel = OutputChannelToProto(e.channel);
  }
  return f;
}

// Every tag above is one byte.
size_t BodySize(const ElementFields& f) {
  size_t size = 0;
  if (f.type != 0)
    size += 1 + CodedOutputStream::VarintSize32SignExtended(f.type);
  if (f.sign != 0)
    size += 1 + CodedOutputStream::VarintSize32SignExtended(f.sign);
  if (f.x != 0) size += 1 + 8;
  if (f.y != 0) size += 1 + 8;
  if (f.channel != 0) {
    size += 1 + CodedOutputStream::VarintSize32SignExtended(f.channel);
  }
  return size;
}

// An int32 or enum field, left out at 0.
uint8_t* PutInt32(uint32_t tag, int32_t value, uint8_t* out) {
  if (value == 0) return out;
  out = CodedOutputStream::WriteTagToArray(tag, out);
  return CodedOutputStream::WriteVarint32SignExtendedToArray(value, out);
}

// A double field by its bits, left out when they are all 0.
uint8_t* PutDouble(uint32_t tag, uint64_t bits, uint8_t* out) {
  if (bits == 0) return out;
  out = CodedOutputStream::WriteTagToArray(tag, out);
  return CodedOutputStream::WriteLittleEndian64ToArray(bits, out);
}

}  // namespace

SerializedGenome SerializeGenome(const Genome& genome) {
  // At most 1 + 1 (tag, length) + 11 + 11 + 9 + 9 + 11 bytes an element.
  constexpr size_t kMaxElementBytes = 53;
  SerializedGenome out;
  out.bytes.resize(genome.elements.size() * kMaxElementBytes);
  uint8_t* const begin = reinterpret_cast<uint8_t*>(out.bytes.data());
  uint8_t* p = begin;
  for (const Element& e : genome.elements) {
    const ElementFields f = Fields(e);
    p = CodedOutputStream::WriteTagToArray(kElementsTag, p);
    p = CodedOutputStream::WriteVarint32ToArray(
        static_cast<uint32_t>(BodySize(f)), p);
    p = PutInt32(kTypeTag, f.type, p);
    p = PutInt32(kSignTag, f.sign, p);
    p = PutDouble(kXTag, f.x, p);
    p = PutDouble(kYTag, f.y, p);
    p = PutInt32(kChannelTag, f.channel, p);
  }
  out.bytes.resize(static_cast<size_t>(p - begin));
  StateHash hash;
  hash.AddBytes(out.bytes);
  out.hash = hash.value();
  out.elements = static_cast<int>(genome.elements.size());
  return out;
}

}  // namespace animat::protocol
