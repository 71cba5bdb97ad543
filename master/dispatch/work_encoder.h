// Work messages assembled from items serialised once: the dispatcher keeps
// each pending individual's WorkItem as bytes and sends those bytes in as
// many Work envelopes as it takes (re-sends included), without copying or
// serialising a genome again.
//
// The bytes are exactly Encode() of the same Envelope (fields in field
// order, as protobuf writes them), so workers decode them as any other.
// Not thread-safe; cheap to make.
#ifndef ANIMAT_MASTER_DISPATCH_WORK_ENCODER_H_
#define ANIMAT_MASTER_DISPATCH_WORK_ENCODER_H_

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "common/protocol/genome_wire.h"

namespace animat {

// The serialisation of WorkItem{individual, genome, genome.hash}.
std::string EncodeWorkItem(uint64_t individual,
                           const protocol::SerializedGenome& genome);

// One Envelope{protocol_version: kVersion, work: Work{config_hash, items,
// config}}.
class WorkEncoder {
 public:
  // `expected_bytes`: of the items to come, if known (saves reallocation).
  explicit WorkEncoder(uint64_t config_hash, size_t expected_bytes = 0);

  // The serialised Config of config_hash, to carry in this message (a
  // worker that may not have it); none by default.
  void SetConfig(std::string_view config) { config_.assign(config); }

  // Appends an item made by EncodeWorkItem.
  void Add(std::string_view item);
  int items() const { return items_; }
  // Of the items added so far.
  size_t item_bytes() const { return items_bytes_; }

  // The envelope's bytes; the encoder is then empty (no items, no
  // config).
  std::string Finish();

 private:
  uint64_t config_hash_;
  std::string config_;  // Serialised; empty: none carried.
  // The envelope: kHeadRoom bytes left for the envelope's and the Work's
  // heads (written by Finish, which then drops the unused room), then the
  // items, so that they are copied once.
  std::string out_;
  int items_ = 0;
  size_t items_bytes_ = 0;
};

}  // namespace animat

#endif  // ANIMAT_MASTER_DISPATCH_WORK_ENCODER_H_
