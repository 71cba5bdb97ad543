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
  Clock::TimePoint idle_since = options_.clock->Now();
  int backoff = options_.reconnect_min_ms;
  while (!stop_.load(std::memory_order_relaxed)) {
    if (IdleTooLong(idle_since)) {
      options_.log("no master for " + std::to_string(options_.idle_timeout_s) +
                   " s; exiting (--idle-timeout)");
      pool_.reset();
      return kExitDone;
    }
    const std::optional<SessionEnd> end = RunSession(context);
    if (!end) return kExitBadEndpoint;
    if (*end == SessionEnd::kRefused) return kExitRefused;
    if (*end == SessionEnd::kStopped) break;
    if (*end == SessionEnd::kRunOver && options_.exit_when_done) {
      options_.log("the master's run is over; exiting (--exit-when-done)");
      pool_.reset();
      return kExitDone;
    }
    if (*end == SessionEnd::kLostAfterWelcome || *end == SessionEnd::kRunOver) {
      backoff = options_.reconnect_min_ms;
      idle_since = options_.clock->Now();
    }
    options_.log(std::string(*end == SessionEnd::kRunOver
                                 ? "the master's run is over; waiting for a "
                                   "next master"
                                 : "master silent") +
                 "; reconnecting in " + std::to_string(backoff) + " ms");
    Backoff(backoff, idle_since);
    backoff = std::min(2 * backoff, options_.reconnect_max_ms);
  }
  pool_.reset();
  options_.log("stopped");
  return kExitStopped;
}

std::optional<Worker::SessionEnd> Worker::RunSession(zmq::context_t& context) {
  try {
    return Session(*this, context).Run();
  } catch (const zmq::error_t& e) {
    // The endpoint was checked (protocol::CheckEndpoint); ZeroMQ may still
    // refuse it.
    options_.log("cannot connect to " + options_.endpoint + ": " + e.what());
    return std::nullopt;
  }
}

bool Worker::IdleTooLong(Clock::TimePoint since) const {
  return options_.idle_timeout_s > 0 &&
         options_.clock->Now() - since >=
             std::chrono::seconds(options_.idle_timeout_s);
}

void Worker::Backoff(int ms, Clock::TimePoint since) {
  for (int waited = 0; waited < ms && !stop_.load() && !IdleTooLong(since);
       waited += 20) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

}  // namespace animat
