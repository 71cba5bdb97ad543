#include "common/protocol/protocol.h"

#include "common/kernels/isa.h"

#include <cmath>
#include <utility>

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

Result<v1::Envelope> Decode(std::string_view frame) {
  v1::Envelope envelope;
  if (!envelope.ParseFromArray(frame.data(), static_cast<int>(frame.size()))) {
    return Status::InvalidArgument("not an animat.v1.Envelope (" +
                                   std::to_string(frame.size()) + " bytes)");
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
  return envelope;
}

Status ValidateResult(const v1::EvaluationResult& r) {
  if (!v1::EvaluationResult::Status_IsValid(r.status()) ||
      r.status() == v1::EvaluationResult::STATUS_UNSPECIFIED) {
    return Status::InvalidArgument("unknown status " +
                                   std::to_string(r.status()));
  }
  const bool ok = r.status() == v1::EvaluationResult::OK;
  if (ok != r.has_fitness()) {
    return Status::InvalidArgument(ok ? "status OK without a fitness"
                                      : "a fitness without status OK");
  }
  if (ok && !(std::isfinite(r.fitness()) && r.fitness() >= 0.0)) {
    return Status::InvalidArgument("fitness " + std::to_string(r.fitness()));
  }
  if (r.has_body()) {
    const v1::BodySummary& b = r.body();
    const std::pair<const char*, int32_t> counts[] = {
        {"cells", b.cells()},
        {"springs", b.springs()},
        {"chambers", b.chambers()},
        {"skin_edges", b.skin_edges()}};
    for (const auto& [name, count] : counts) {
      if (count < 0) {
        return Status::InvalidArgument(std::string("body ") + name + " " +
                                       std::to_string(count));
      }
    }
    const std::pair<const char*, double> spreads[] = {
        {"spread_major", b.spread_major()}, {"spread_minor", b.spread_minor()}};
    for (const auto& [name, spread] : spreads) {
      if (!(std::isfinite(spread) && spread >= 0.0)) {
        return Status::InvalidArgument(std::string("body ") + name + " " +
                                       std::to_string(spread));
      }
    }
    if (b.spread_minor() > b.spread_major()) {
      return Status::InvalidArgument(
          "body spread_minor " + std::to_string(b.spread_minor()) +
          " above spread_major " + std::to_string(b.spread_major()));
    }
  }
  return Status::Ok();
}

const char* BodyName(const v1::Envelope& envelope) {
  switch (envelope.body_case()) {
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
