// protocol::SerializeGenome(const Genome&): animat.v1.Genome's wire bytes
// written straight from a Genome, byte for byte what protobuf writes for
// GenomeToProto(genome) (tests/dispatch/genome_encoder_test.cc compares
// them): fields in field order, proto3 defaults (0, and doubles whose bits
// are all 0) left out, negative int32 and enum values as 10-byte varints.
#include <cstring>

#include "common/base/hash.h"
#include "common/protocol/protocol.h"

namespace animat::protocol {
namespace {

// animat.v1.Element's field tags (field number << 3 | wire type).
constexpr uint8_t kTypeTag = 1 << 3 | 0;     // varint
constexpr uint8_t kSignTag = 2 << 3 | 0;     // varint
constexpr uint8_t kXTag = 3 << 3 | 1;        // fixed64
constexpr uint8_t kYTag = 4 << 3 | 1;        // fixed64
constexpr uint8_t kChannelTag = 5 << 3 | 0;  // varint
// animat.v1.Genome.elements: field 1, length-delimited.
constexpr uint8_t kElementsTag = 1 << 3 | 2;

// animat.v1.Element.Channel values of the first input and output channels
// (genome_proto.cc maps the same way).
constexpr int kFirstInput = v1::Element::MATERNAL_0;
constexpr int kFirstOutput = v1::Element::DIVIDE;

// An int32 or enum field's varint: negative values are sign-extended to 64
// bits, as protobuf writes them.
uint64_t Int32Varint(int32_t value) {
  return static_cast<uint64_t>(static_cast<int64_t>(value));
}

size_t VarintSize(uint64_t value) {
  size_t size = 1;
  while (value >= 0x80) {
    value >>= 7;
    ++size;
  }
  return size;
}

// Writers at a cursor into a buffer sized for the worst case.
char* PutVarint(uint64_t value, char* out) {
  while (value >= 0x80) {
    *out++ = static_cast<char>(value | 0x80);
    value >>= 7;
  }
  *out++ = static_cast<char>(value);
  return out;
}

char* PutFixed64(uint64_t bits, char* out) {
  for (int i = 0; i < 8; ++i) *out++ = static_cast<char>(bits >> (8 * i));
  return out;
}

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
  if (e.type == ElementType::kSIn) f.channel = kFirstInput + e.channel;
  if (e.type == ElementType::kSOut) f.channel = kFirstOutput + e.channel;
  return f;
}

size_t BodySize(const ElementFields& f) {
  size_t size = 0;
  if (f.type != 0) size += 1 + VarintSize(Int32Varint(f.type));
  if (f.sign != 0) size += 1 + VarintSize(Int32Varint(f.sign));
  if (f.x != 0) size += 1 + 8;
  if (f.y != 0) size += 1 + 8;
  if (f.channel != 0) size += 1 + VarintSize(Int32Varint(f.channel));
  return size;
}

}  // namespace

SerializedGenome SerializeGenome(const Genome& genome) {
  // At most 1 + 1 (tag, length) + 11 + 11 + 9 + 9 + 11 bytes an element.
  constexpr size_t kMaxElementBytes = 53;
  SerializedGenome out;
  out.bytes.resize(genome.elements.size() * kMaxElementBytes);
  char* const begin = out.bytes.data();
  char* p = begin;
  for (const Element& e : genome.elements) {
    const ElementFields f = Fields(e);
    *p++ = static_cast<char>(kElementsTag);
    p = PutVarint(BodySize(f), p);
    if (f.type != 0) {
      *p++ = static_cast<char>(kTypeTag);
      p = PutVarint(Int32Varint(f.type), p);
    }
    if (f.sign != 0) {
      *p++ = static_cast<char>(kSignTag);
      p = PutVarint(Int32Varint(f.sign), p);
    }
    if (f.x != 0) {
      *p++ = static_cast<char>(kXTag);
      p = PutFixed64(f.x, p);
    }
    if (f.y != 0) {
      *p++ = static_cast<char>(kYTag);
      p = PutFixed64(f.y, p);
    }
    if (f.channel != 0) {
      *p++ = static_cast<char>(kChannelTag);
      p = PutVarint(Int32Varint(f.channel), p);
    }
  }
  out.bytes.resize(static_cast<size_t>(p - begin));
  StateHash hash;
  hash.AddBytes(out.bytes);
  out.hash = hash.value();
  out.elements = static_cast<int>(genome.elements.size());
  return out;
}

}  // namespace animat::protocol
