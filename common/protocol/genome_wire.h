// Genomes and configurations as bytes: the deterministic serialisation the
// master stores and sends, and the 64-bit fingerprints (FNV-1a) that name a
// genome or a configuration in the protocol and the lineage store.
//
// No simulator here (the lineage store and `animat lineage` link this, not
// the evaluator): protobuf, the schema and the Genome type only. All
// functions are pure and thread-safe; none fails.
#ifndef ANIMAT_COMMON_PROTOCOL_GENOME_WIRE_H_
#define ANIMAT_COMMON_PROTOCOL_GENOME_WIRE_H_

#include <cstdint>
#include <string>

#include <google/protobuf/message_lite.h>

#include "animat/v1/config.pb.h"
#include "animat/v1/genome.pb.h"
#include "common/genome/genome.h"

namespace animat::protocol {

// 64-bit fingerprints of the deterministic serialisation (FNV-1a): the
// config a session runs with, the genome an individual carries.
uint64_t ConfigHash(const v1::Config& config);
uint64_t GenomeHash(const v1::Genome& genome);
// The same for any message.
uint64_t MessageHash(const google::protobuf::MessageLite& message);

// A genome's deterministic serialisation with its GenomeHash, made once
// for whoever needs both (the lineage store, the dispatcher).
struct SerializedGenome {
  std::string bytes;
  uint64_t hash = 0;
  int elements = 0;  // The genome's length.
};
SerializedGenome SerializeGenome(const v1::Genome& genome);
// The same bytes, hash and length as SerializeGenome(GenomeToProto(genome)),
// written directly without building the message (the master makes
// thousands of genomes a second; genome_encoder.cc).
SerializedGenome SerializeGenome(const Genome& genome);

}  // namespace animat::protocol

#endif  // ANIMAT_COMMON_PROTOCOL_GENOME_WIRE_H_
