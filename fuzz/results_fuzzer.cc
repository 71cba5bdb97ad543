// libFuzzer target: what the master checks in a worker's Results before
// recording them: the envelope decoded, then protocol::ValidateResult on
// every result. An accepted result must be one the master can record.
#include <cmath>
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
  Result<v1::Envelope> envelope = protocol::Decode(
      std::string_view(reinterpret_cast<const char*>(data), size));
  if (!envelope.ok() || !envelope->has_results()) return 0;
  for (const v1::WorkResult& r : envelope->results().results()) {
    const v1::EvaluationResult& result = r.result();
    const Status valid = protocol::ValidateResult(result);
    if (!valid.ok()) {
      if (valid.message().empty()) std::abort();
      continue;
    }
    if (result.status() == v1::EvaluationResult::STATUS_UNSPECIFIED ||
        !v1::EvaluationResult::Status_IsValid(result.status())) {
      std::abort();
    }
    const bool ok = result.status() == v1::EvaluationResult::OK;
    if (ok != result.has_fitness()) std::abort();
    // Only a guidance score (with its source distances) may be negative.
    const bool guidance = result.source_distances_size() > 0;
    if (ok && !(std::isfinite(result.fitness()) &&
                (guidance || result.fitness() >= 0))) {
      std::abort();
    }
    if (guidance && !ok) std::abort();
    for (double d : result.source_distances()) {
      if (!(std::isfinite(d) && d >= 0)) std::abort();
    }
    if (result.has_body()) {
      const v1::BodySummary& b = result.body();
      if (b.cells() < 0 || b.springs() < 0 || b.chambers() < 0 ||
          b.skin_edges() < 0) {
        std::abort();
      }
      if (!(std::isfinite(b.spread_major()) &&
            std::isfinite(b.spread_minor()) && b.spread_minor() >= 0 &&
            b.spread_major() >= b.spread_minor())) {
        std::abort();
      }
    }
  }
  return 0;
}
