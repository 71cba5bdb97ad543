#include "common/protocol/genome_wire.h"

#include <google/protobuf/io/coded_stream.h>
#include <google/protobuf/io/zero_copy_stream_impl_lite.h>

#include "common/base/hash.h"

namespace animat::protocol {
namespace {

std::string Deterministic(const google::protobuf::MessageLite& message) {
  std::string out;
  {
    google::protobuf::io::StringOutputStream stream(&out);
    google::protobuf::io::CodedOutputStream coded(&stream);
    coded.SetSerializationDeterministic(true);
    message.SerializeToCodedStream(&coded);
  }
  return out;
}

uint64_t Fingerprint(const std::string& bytes) {
  StateHash hash;
  hash.AddBytes(bytes);
  return hash.value();
}

}  // namespace

uint64_t ConfigHash(const v1::Config& config) {
  return Fingerprint(Deterministic(config));
}

uint64_t MessageHash(const google::protobuf::MessageLite& message) {
  return Fingerprint(Deterministic(message));
}

uint64_t GenomeHash(const v1::Genome& genome) {
  return Fingerprint(Deterministic(genome));
}

SerializedGenome SerializeGenome(const v1::Genome& genome) {
  SerializedGenome out;
  out.bytes = Deterministic(genome);
  out.hash = Fingerprint(out.bytes);
  out.elements = genome.elements_size();
  return out;
}

}  // namespace animat::protocol
