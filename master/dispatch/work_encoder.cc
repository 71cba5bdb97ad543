#include "master/dispatch/work_encoder.h"

#include <algorithm>

#include <google/protobuf/io/coded_stream.h>

#include "common/protocol/protocol.h"

namespace animat {
namespace {

using google::protobuf::io::CodedOutputStream;

// Wire types and field numbers of animat/v1/protocol.proto.
constexpr uint32_t kVarint = 0;
constexpr uint32_t kFixed64 = 1;
constexpr uint32_t kLengthDelimited = 2;
constexpr uint32_t kEnvelopeProtocolVersion = 1;
constexpr uint32_t kEnvelopeWork = 14;
constexpr uint32_t kWorkConfigHash = 1;
constexpr uint32_t kWorkItems = 2;
constexpr uint32_t kWorkConfig = 3;
constexpr uint32_t kItemIndividual = 1;
constexpr uint32_t kItemGenome = 2;
constexpr uint32_t kItemGenomeHash = 3;

// The writers are protobuf's (CodedOutputStream), into a few bytes on the
// stack that are then appended: the items themselves are copied once.
void Append(const uint8_t* begin, const uint8_t* end, std::string* out) {
  out->append(reinterpret_cast<const char*>(begin),
              static_cast<size_t>(end - begin));
}

void AppendVarint(uint64_t value, std::string* out) {
  uint8_t bytes[10];
  Append(bytes, CodedOutputStream::WriteVarint64ToArray(value, bytes), out);
}

void AppendTag(uint32_t field, uint32_t wire_type, std::string* out) {
  uint8_t bytes[5];
  Append(bytes,
         CodedOutputStream::WriteTagToArray((field << 3) | wire_type, bytes),
         out);
}

void AppendFixed64(uint32_t field, uint64_t value, std::string* out) {
  AppendTag(field, kFixed64, out);
  uint8_t bytes[8];
  Append(bytes, CodedOutputStream::WriteLittleEndian64ToArray(value, bytes),
         out);
}

void AppendBytes(uint32_t field, std::string_view bytes, std::string* out) {
  AppendTag(field, kLengthDelimited, out);
  AppendVarint(bytes.size(), out);
  out->append(bytes);
}

}  // namespace

// Proto3 leaves scalar fields at their default value out; so do these.

std::string EncodeWorkItem(uint64_t individual,
                           const protocol::SerializedGenome& genome) {
  std::string out;
  out.reserve(genome.bytes.size() + 24);
  if (individual != 0) {
    AppendTag(kItemIndividual, kVarint, &out);
    AppendVarint(individual, &out);
  }
  AppendBytes(kItemGenome, genome.bytes, &out);  // A message: always.
  if (genome.hash != 0) AppendFixed64(kItemGenomeHash, genome.hash, &out);
  return out;
}

// Room for the heads: the version field (2 bytes), the work tag (1) and
// length (at most 10), the config hash field (9).
constexpr size_t kHeadRoom = 32;

WorkEncoder::WorkEncoder(uint64_t config_hash, size_t expected_bytes)
    : config_hash_(config_hash), out_(kHeadRoom, '\0') {
  if (expected_bytes > 0) out_.reserve(kHeadRoom + expected_bytes);
}

void WorkEncoder::Add(std::string_view item) {
  if (out_.capacity() < out_.size() + item.size() + 16) {
    // Whole batches are the rule: grow in large steps.
    out_.reserve(
        std::max(2 * out_.capacity(), out_.size() + 64 * (item.size() + 16)));
  }
  AppendBytes(kWorkItems, item, &out_);
  ++items_;
  items_bytes_ += item.size();
}

std::string WorkEncoder::Finish() {
  // The carried config is the last field (field order, as protobuf
  // writes it): after the items.
  if (!config_.empty()) AppendBytes(kWorkConfig, config_, &out_);
  std::string config;
  if (config_hash_ != 0) AppendFixed64(kWorkConfigHash, config_hash_, &config);
  const size_t items = out_.size() - kHeadRoom;
  std::string head;
  AppendTag(kEnvelopeProtocolVersion, kVarint, &head);
  AppendVarint(protocol::kVersion, &head);
  AppendTag(kEnvelopeWork, kLengthDelimited, &head);
  AppendVarint(config.size() + items, &head);
  head += config;
  // The heads go just before the items; the room left over is dropped.
  const size_t start = kHeadRoom - head.size();
  out_.replace(start, head.size(), head);
  out_.erase(0, start);
  std::string out;
  out.swap(out_);
  out_.assign(kHeadRoom, '\0');
  config_.clear();
  items_ = 0;
  items_bytes_ = 0;
  return out;
}

}  // namespace animat
