#include "common/protocol/protocol.h"

#include <google/protobuf/io/coded_stream.h>
#include <google/protobuf/wire_format_lite.h>

#include <cmath>
#include <utility>

#include "common/kernels/isa.h"
#include "common/protocol/build_info.h"

namespace animat::protocol {

const std::string& BuildId() {
  static const std::string id = std::string("animat ") + kBuildVersion + " " +
                                kBuildCommit + " " + kBuildCompiler + " " +
                                kBuildArch;
  return id;
}

std::string VersionText() {
  return "build: " + BuildId() + "\nprotocol: " + std::to_string(kVersion) +
         "\nmodel: " + std::to_string(kModelVersion) +
         "\nkernels: " + IsaReport();
}

std::string Encode(v1::Envelope envelope) {
  envelope.set_protocol_version(kVersion);
  return envelope.SerializeAsString();
}

namespace {

// What a frame says about itself before it is parsed: a walk over its
// top-level fields that skips their contents (a length-delimited field
// costs its length's bytes, not its payload's).
struct FrameHead {
  v1::Envelope::BodyCase body = v1::Envelope::BODY_NOT_SET;
};

bool ReadHead(std::string_view frame, FrameHead* head) {
  using google::protobuf::internal::WireFormatLite;
  google::protobuf::io::CodedInputStream in(
      reinterpret_cast<const uint8_t*>(frame.data()),
      static_cast<int>(frame.size()));
  while (const uint32_t tag = in.ReadTag()) {
    const int field = WireFormatLite::GetTagFieldNumber(tag);
    // The body's fields are numbered 10 (hello) to 18 (acknowledge).
    if (WireFormatLite::GetTagWireType(tag) ==
            WireFormatLite::WIRETYPE_LENGTH_DELIMITED &&
        field >= v1::Envelope::kHelloFieldNumber &&
        field <= v1::Envelope::kAcknowledgeFieldNumber) {
      head->body = static_cast<v1::Envelope::BodyCase>(field);
    }
    if (!WireFormatLite::SkipField(&in, tag)) return false;
  }
  return in.ConsumedEntireMessage();
}

}  // namespace

Result<v1::Envelope> Decode(std::string_view frame) {
  const auto not_envelope = [&] {
    return Status::InvalidArgument("not an animat.v1.Envelope (" +
                                   std::to_string(frame.size()) + " bytes)");
  };
  FrameHead head;
  if (frame.size() > static_cast<size_t>(kMaxMessageBytes) ||
      !ReadHead(frame, &head)) {
    return not_envelope();
  }
  // Refused before it is parsed: a frame larger than its body may take.
  const size_t limit = MaxEnvelopeBytes(head.body);
  if (frame.size() > limit) {
    return Status::InvalidArgument(std::string("a ") + BodyName(head.body) +
                                   " of " + std::to_string(frame.size()) +
                                   " bytes, above the limit of " +
                                   std::to_string(limit));
  }
  v1::Envelope envelope;
  if (!envelope.ParseFromArray(frame.data(), static_cast<int>(frame.size()))) {
    return not_envelope();
  }
  // A hello and a refuse of another version still decode: they carry what
  // the other side needs to refuse, or to know it was refused.
  if (envelope.protocol_version() != kVersion && !envelope.has_hello() &&
      !envelope.has_refuse()) {
    return Status::InvalidArgument("protocol version " +
                                   std::to_string(envelope.protocol_version()) +
                                   ", expected " + std::to_string(kVersion));
  }
  if (envelope.body_case() == v1::Envelope::BODY_NOT_SET) {
    return Status::InvalidArgument("envelope without a body");
  }
  Status status = CheckEnvelope(envelope);
  if (!status.ok()) return status;
  return envelope;
}

const char* BodyName(const v1::Envelope& envelope) {
  return BodyName(envelope.body_case());
}

const char* BodyName(v1::Envelope::BodyCase body) {
  switch (body) {
    case v1::Envelope::kHello:
      return "hello";
    case v1::Envelope::kWelcome:
      return "welcome";
    case v1::Envelope::kRefuse:
      return "refuse";
    case v1::Envelope::kCredit:
      return "credit";
    case v1::Envelope::kWork:
      return "work";
    case v1::Envelope::kResults:
      return "results";
    case v1::Envelope::kHeartbeat:
      return "heartbeat";
    case v1::Envelope::kGoodbye:
      return "goodbye";
    case v1::Envelope::kAcknowledge:
      return "acknowledge";
    case v1::Envelope::BODY_NOT_SET:
      return "none";
  }
  return "unknown";
}

}  // namespace animat::protocol
