// libFuzzer target: protocol::Decode on arbitrary bytes, as both sides run
// it on every frame from the network, then BodyName for the log line.
// A decoded envelope of this protocol version must re-encode to bytes that
// decode again.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "common/protocol/protocol.h"
#include "fuzz/fuzz_common.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  animat::fuzz::QuietProtobufLogs();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace animat;
  const std::string_view frame(reinterpret_cast<const char*>(data), size);
  Result<v1::Envelope> envelope = protocol::Decode(frame);
  if (!envelope.ok()) {
    if (envelope.status().message().empty()) std::abort();
    return 0;
  }
  const std::string_view name = protocol::BodyName(*envelope);
  if (name == "none" || name == "unknown") std::abort();
  // Encode writes this build's protocol version; a hello or refuse of
  // another version decodes checked for its strings only (its numbers
  // follow that version's rules), so only this version's envelopes must
  // survive the round trip.
  if (envelope->protocol_version() == protocol::kVersion &&
      !protocol::Decode(protocol::Encode(*envelope)).ok()) {
    std::abort();
  }
  return 0;
}
