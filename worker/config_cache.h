// The model configurations a worker has been given (the welcome's, and
// those Work messages carried), by hash: at most protocol::kMaxConfigs,
// the least recently used forgotten first, so that a master sending ever
// more configurations costs the worker bounded memory. A master never
// uses more at once (docs/protocol.md), so a conforming one is never
// forgotten while in use.
//
// Not thread-safe: the worker's session thread uses it; the
// configurations it hands out are immutable and may be shared with the
// evaluation threads.
#ifndef ANIMAT_WORKER_CONFIG_CACHE_H_
#define ANIMAT_WORKER_CONFIG_CACHE_H_

#include <cstdint>
#include <list>
#include <memory>
#include <utility>

#include "animat/v1/config.pb.h"
#include "common/base/status.h"
#include "common/evaluation/model_config.h"

namespace animat {

class ConfigCache {
 public:
  // Keeps `config` under `hash`, as the most recently used, after checking
  // that it hashes to `hash` (protocol::ConfigHash) and is a valid model
  // configuration; fails, saying which, and keeps nothing otherwise. One
  // already kept is only made the most recent.
  Result<std::shared_ptr<const ModelConfig>> Put(const v1::Config& config,
                                                 uint64_t hash);
  // The configuration kept under `hash`, made the most recently used; null
  // when there is none.
  std::shared_ptr<const ModelConfig> Get(uint64_t hash);
  size_t size() const { return kept_.size(); }

 private:
  // Most recently used first.
  std::list<std::pair<uint64_t, std::shared_ptr<const ModelConfig>>> kept_;
};

}  // namespace animat

#endif  // ANIMAT_WORKER_CONFIG_CACHE_H_
