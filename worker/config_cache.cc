#include "worker/config_cache.h"

#include <cstdio>
#include <string>

#include "common/protocol/genome_wire.h"
#include "common/protocol/protocol.h"

namespace animat {
namespace {

std::string Hex(uint64_t hash) {
  char text[17];
  std::snprintf(text, sizeof(text), "%016llx",
                static_cast<unsigned long long>(hash));
  return text;
}

}  // namespace

std::shared_ptr<const ModelConfig> ConfigCache::Get(uint64_t hash) {
  for (auto it = kept_.begin(); it != kept_.end(); ++it) {
    if (it->first == hash) {
      kept_.splice(kept_.begin(), kept_, it);
      return kept_.front().second;
    }
  }
  return nullptr;
}

Result<std::shared_ptr<const ModelConfig>> ConfigCache::Put(
    const v1::Config& config, uint64_t hash) {
  const uint64_t actual = protocol::ConfigHash(config);
  if (actual != hash) {
    return Status::InvalidArgument("configuration " + Hex(hash) +
                                   " hashes to " + Hex(actual));
  }
  if (std::shared_ptr<const ModelConfig> kept = Get(hash)) return kept;
  auto made = std::make_shared<ModelConfig>();
  Status status = ConfigFromProto(config, made.get());
  if (!status.ok()) return status.WithPrefix("configuration " + Hex(hash));
  kept_.emplace_front(hash, std::move(made));
  if (kept_.size() > protocol::kMaxConfigs) kept_.pop_back();
  return kept_.front().second;
}

}  // namespace animat
