#include "worker/worker.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <random>
#include <thread>
#include <zmq.hpp>

#include "worker/evaluation_pool.h"
#include "worker/session.h"

namespace animat {

Worker::Worker(WorkerOptions options) : options_(std::move(options)) {
  char name[256] = {};
  if (gethostname(name, sizeof(name) - 1) == 0) host_ = name;
  std::random_device device;
  while (instance_ == 0) {
    instance_ = uint64_t{device()} << 32 | device();
  }
}

Worker::~Worker() = default;

int Worker::Run() {
  zmq::context_t context(1);
  int backoff = options_.reconnect_min_ms;
  while (!stop_.load(std::memory_order_relaxed)) {
    SessionEnd end;
    try {
      end = Session(*this, context).Run();
    } catch (const zmq::error_t& e) {
      // The endpoint was checked (protocol::CheckEndpoint); ZeroMQ may
      // still refuse it.
      options_.log("cannot connect to " + options_.endpoint + ": " + e.what());
      return kExitBadEndpoint;
    }
    if (end == SessionEnd::kRefused) return kExitRefused;
    if (end == SessionEnd::kStopped) break;
    if (end == SessionEnd::kLostAfterWelcome) {
      backoff = options_.reconnect_min_ms;
    }
    options_.log("master silent; reconnecting in " + std::to_string(backoff) +
                 " ms");
    for (int waited = 0; waited < backoff && !stop_.load(); waited += 20) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    backoff = std::min(2 * backoff, options_.reconnect_max_ms);
  }
  pool_.reset();
  options_.log("stopped");
  return kExitStopped;
}

}  // namespace animat
