// libFuzzer target: the worker's side of what a master sends it. A Work
// message's items go through GenomeFromProto, as on the worker's pool
// threads, and a valid genome is built into its network and checked for
// viability (the first steps of an evaluation; the simulation itself is
// too slow to fuzz). A Welcome's configuration, and one a Work carries, go
// into the worker's ConfigCache (its hash and ConfigFromProto checked), as
// in the worker's session.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "common/evaluation/model_config.h"
#include "common/genome/genome_proto.h"
#include "common/grn/network.h"
#include "common/protocol/genome_wire.h"
#include "common/protocol/protocol.h"
#include "fuzz/fuzz_common.h"
#include "worker/config_cache.h"

namespace {

// Genomes with more elements are validated but not built, so that every
// input stays cheap (building is quadratic in the elements).
constexpr int kMaxBuiltElements = 300;

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  animat::fuzz::QuietProtobufLogs();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace animat;
  Result<v1::Envelope> envelope = protocol::Decode(
      std::string_view(reinterpret_cast<const char*>(data), size));
  if (!envelope.ok()) return 0;
  ConfigCache configs;
  if (envelope->has_welcome()) {
    const v1::Welcome& welcome = envelope->welcome();
    const auto kept = configs.Put(welcome.config(), welcome.config_hash());
    if (!kept.ok() && kept.status().message().empty()) std::abort();
    return 0;
  }
  if (!envelope->has_work()) return 0;
  if (envelope->work().has_config()) {
    const auto kept =
        configs.Put(envelope->work().config(), envelope->work().config_hash());
    if (!kept.ok() && kept.status().message().empty()) std::abort();
    if (kept.ok() && configs.Get(envelope->work().config_hash()) == nullptr) {
      std::abort();
    }
  }
  const GrnParams params;
  for (const v1::WorkItem& item : envelope->work().items()) {
    Result<Genome> genome = GenomeFromProto(item.genome());
    if (!genome.ok()) {
      if (genome.status().message().empty()) std::abort();
      continue;
    }
    if (genome->elements.size() > kMaxBuiltElements) continue;
    const Network network = Network::Build(*genome, params);
    const Viability viability = network.CheckViability();
    if (!viability.viable && viability.reason.empty()) std::abort();
  }
  return 0;
}
