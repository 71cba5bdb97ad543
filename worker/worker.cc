#include "worker/worker.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <random>
#include <thread>
#include <zmq.hpp>

#include "common/evaluation/model_config.h"
#include "common/protocol/genome_wire.h"
#include "common/protocol/protocol.h"
#include "common/protocol/zmq_poll.h"
#include "worker/evaluation_pool.h"

namespace animat {
namespace {

using Clock = std::chrono::steady_clock;

int64_t MillisSince(Clock::time_point t) {
  return std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - t)
      .count();
}

// Results kept for a next master at most (a few hundred bytes each).
constexpr size_t kMaxUnacknowledged = 100000;

}  // namespace

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
    const SessionEnd end = RunSession(context);
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

Worker::SessionEnd Worker::RunSession(zmq::context_t& context) {
  zmq::socket_t socket(context, zmq::socket_type::dealer);
  socket.set(zmq::sockopt::linger, 0);
  socket.set(zmq::sockopt::maxmsgsize, protocol::kMaxMessageBytes);
  if (!options_.curve_server_key.empty()) {
    socket.set(zmq::sockopt::curve_serverkey, options_.curve_server_key);
    socket.set(zmq::sockopt::curve_publickey, options_.curve_public_key);
    socket.set(zmq::sockopt::curve_secretkey, options_.curve_secret_key);
  }
  socket.connect(options_.endpoint);

  Clock::time_point last_heard = Clock::now();
  Clock::time_point last_sent = Clock::now();
  int heartbeat_ms = options_.heartbeat_ms;
  bool welcomed = false;
  uint64_t config_hash = 0;
  bool stopping = false;
  std::vector<uint64_t> returned;
  int uncredited = 0;  // Results finished before this session's welcome.
  bool warned_unacknowledged = false;

  auto send = [&](const v1::Envelope& envelope) {
    const std::string bytes = protocol::Encode(envelope);
    const zmq::send_result_t sent =
        socket.send(zmq::buffer(bytes), zmq::send_flags::dontwait);
    if (!sent) {
      options_.log(std::string("could not send ") +
                   protocol::BodyName(envelope) + " (no connection)");
    }
    last_sent = Clock::now();
  };
  auto send_credit = [&](int credit) {
    if (credit <= 0) return;
    v1::Envelope envelope;
    envelope.mutable_credit()->set_credit(credit);
    send(envelope);
  };

  {
    v1::Envelope hello;
    v1::Hello* h = hello.mutable_hello();
    h->set_protocol_version(protocol::kVersion);
    h->set_build_id(protocol::BuildId());
    h->set_threads(options_.threads);
    h->set_host(host_);
    h->set_pid(static_cast<uint64_t>(getpid()));
    h->set_null_evaluation(options_.null_evaluation);
    h->set_instance(instance_);
    send(hello);
  }

  for (;;) {
    if (stop_.load(std::memory_order_relaxed) && !stopping) {
      if (!welcomed) return SessionEnd::kStopped;
      stopping = true;
      returned = pool_ ? pool_->Abandon() : std::vector<uint64_t>{};
      options_.log("stopping: handing back " + std::to_string(returned.size()) +
                   " items, finishing " +
                   std::to_string(pool_ ? pool_->in_flight() : 0));
    }
    if (stopping && (!pool_ || pool_->in_flight() == 0)) {
      if (pool_) {
        for (v1::WorkResult& r : pool_->TakeFinished()) {
          unsent_.push_back(std::move(r));
        }
      }
      if (!unsent_.empty()) {
        v1::Envelope results;
        for (v1::WorkResult& r : unsent_) {
          *results.mutable_results()->add_results() = std::move(r);
        }
        unsent_.clear();
        send(results);
      }
      v1::Envelope goodbye;
      for (uint64_t id : returned) goodbye.mutable_goodbye()->add_returned(id);
      goodbye.mutable_goodbye()->set_reason("worker stopping");
      send(goodbye);
      return SessionEnd::kStopped;
    }

    zmq::pollitem_t items[2] = {
        {static_cast<void*>(socket), 0, ZMQ_POLLIN, 0},
        {nullptr, pool_ ? pool_->wakeup_fd() : -1, ZMQ_POLLIN, 0}};
    const int count = pool_ ? 2 : 1;
    const long timeout =
        std::max<long>(1, std::min<long>(heartbeat_ms - MillisSince(last_sent),
                                         stopping ? 20 : 100));
    protocol::Poll(items, count, std::chrono::milliseconds(timeout));

    if (items[0].revents & ZMQ_POLLIN) {
      zmq::message_t frame;
      while (socket.recv(frame, zmq::recv_flags::dontwait)) {
        if (frame.more()) {
          // A multi-frame message is not ours: drain and drop it.
          options_.log("ignored a multi-frame message from the master");
          while (frame.more() &&
                 socket.recv(frame, zmq::recv_flags::dontwait)) {
          }
          continue;
        }
        Result<v1::Envelope> decoded = protocol::Decode(frame.to_string_view());
        if (!decoded.ok()) {
          options_.log("ignored a malformed message from the master: " +
                       decoded.status().message());
          continue;
        }
        last_heard = Clock::now();
        const v1::Envelope& envelope = *decoded;
        switch (envelope.body_case()) {
          case v1::Envelope::kWelcome: {
            const v1::Welcome& welcome = envelope.welcome();
            ModelConfig config;
            Status status = ConfigFromProto(welcome.config(), &config);
            if (!status.ok() || protocol::ConfigHash(welcome.config()) !=
                                    welcome.config_hash()) {
              options_.log("ignored a welcome with a bad configuration: " +
                           (status.ok() ? std::string("hash mismatch")
                                        : status.message()));
              break;
            }
            welcomed = true;
            config_hash = welcome.config_hash();
            if (welcome.heartbeat_ms() > 0) {
              heartbeat_ms = static_cast<int>(welcome.heartbeat_ms());
            }
            if (!pool_ || pool_config_hash_ != config_hash) {
              pool_ = std::make_unique<EvaluationPool>(
                  options_.threads, config, options_.null_evaluation);
              pool_config_hash_ = config_hash;
            }
            options_.log("welcomed by " + options_.endpoint + " (" +
                         std::to_string(options_.threads) + " threads)");
            send_credit(options_.threads * protocol::kPrefetch -
                        pool_->in_flight());
            uncredited = static_cast<int>(unsent_.size());
            if (!unacknowledged_.empty()) {
              // The last master may have died before recording them; this
              // one takes those it still needs (they earn no credit: they
              // were counted in the session that ran them).
              options_.log("sending again " +
                           std::to_string(unacknowledged_.size()) +
                           " results not acknowledged by the last master");
              v1::Envelope results;
              for (const auto& [id, result] : unacknowledged_) {
                *results.mutable_results()->add_results() = result;
                if (results.results().results_size() == protocol::kMaxBatch) {
                  send(results);
                  results.mutable_results()->clear_results();
                }
              }
              if (results.results().results_size() > 0) send(results);
            }
            break;
          }
          case v1::Envelope::kRefuse:
            options_.log("refused by the master: " +
                         envelope.refuse().reason());
            return SessionEnd::kRefused;
          case v1::Envelope::kWork: {
            const v1::Work& work = envelope.work();
            if (!welcomed || work.config_hash() != config_hash) {
              options_.log("ignored work for configuration " +
                           std::to_string(work.config_hash()) +
                           (welcomed ? "" : " before a welcome"));
              break;
            }
            for (const v1::WorkItem& item : work.items()) {
              if (stopping) {
                returned.push_back(item.individual());  // Handed back.
              } else {
                pool_->Submit(item);
              }
            }
            break;
          }
          case v1::Envelope::kHeartbeat:
            break;
          case v1::Envelope::kAcknowledge:
            for (uint64_t id : envelope.acknowledge().individuals()) {
              unacknowledged_.erase(id);
            }
            break;
          default:
            options_.log(std::string("ignored an unexpected ") +
                         protocol::BodyName(envelope) + " from the master");
            break;
        }
      }
    }

    if (pool_ && (items[1].revents & ZMQ_POLLIN)) {
      std::vector<v1::WorkResult> finished_now = pool_->TakeFinished();
      for (v1::WorkResult& r : finished_now) unsent_.push_back(std::move(r));
    }
    if (welcomed && !unsent_.empty()) {
      // Results wait here for a session that welcomed us; a new master
      // takes those it still needs and ignores the rest.
      std::vector<v1::WorkResult> done;
      done.swap(unsent_);
      for (size_t begin = 0; begin < done.size();
           begin += protocol::kMaxBatch) {
        v1::Envelope results;
        const size_t end = std::min(done.size(), begin + protocol::kMaxBatch);
        for (size_t i = begin; i < end; ++i) {
          if (unacknowledged_.size() < kMaxUnacknowledged) {
            unacknowledged_[done[i].individual()] = done[i];
          } else if (!warned_unacknowledged) {
            warned_unacknowledged = true;
            options_.log("the master has not acknowledged " +
                         std::to_string(kMaxUnacknowledged) +
                         " results; no more are kept for a next master");
          }
          *results.mutable_results()->add_results() = std::move(done[i]);
        }
        send(results);
      }
      // Results that finished before the welcome were not in flight when
      // its credit was counted: they earn none now.
      const int earned = static_cast<int>(done.size()) - uncredited;
      uncredited = std::max(0, uncredited - static_cast<int>(done.size()));
      if (!stopping) send_credit(earned);
    }

    if (MillisSince(last_sent) >= heartbeat_ms) {
      v1::Envelope heartbeat;
      heartbeat.mutable_heartbeat();
      send(heartbeat);
    }
    if (MillisSince(last_heard) > protocol::kLiveness * heartbeat_ms) {
      if (stopping) return SessionEnd::kStopped;
      if (pool_) pool_->Abandon();  // The next master re-sends what it needs.
      return welcomed ? SessionEnd::kLostAfterWelcome : SessionEnd::kLost;
    }
  }
}

}  // namespace animat
