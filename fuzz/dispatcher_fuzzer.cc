// libFuzzer target: the master's dispatcher end to end. One Dispatcher,
// bound on an inproc:// endpoint, lives across inputs with individuals
// 1..kIndividuals always pending; two DEALER peers in the same context
// talk to it. Each input is a few messages of 1 to 4 frames (fuzz_common.h
// has the format), each sent by the worker peer or by a stranger and
// followed by a poll; then the worker peer says a valid hello and the
// dispatcher is polled until it welcomes it. Short heartbeats and leases make
// silence, expiry and giving up happen within a few inputs.
//
// Checked: the dispatcher never crashes, throws or trips a sanitizer;
// it answers the valid hello within 5 s; every message it sends decodes;
// no individual completes twice; its pending count matches ours.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <set>
#include <string>
#include <string_view>
#include <zmq.hpp>

#include "common/evaluation/model_config.h"
#include "common/protocol/protocol.h"
#include "fuzz/fuzz_common.h"
#include "master/dispatch/dispatcher.h"

namespace animat::fuzz {
namespace {

[[noreturn]] void Fail(const std::string& what) {
  std::fprintf(stderr, "dispatcher_fuzzer: %s\n", what.c_str());
  std::abort();
}

class Harness {
 public:
  Harness() {
    DispatcherOptions options;
    options.endpoint = "inproc://dispatcher-fuzzer";
    options.heartbeat_ms = 50;
    options.lease_ms = 20;
    options.accept_null_workers = true;
    options.log = [this](std::string_view line) {
      if (line.find(expected_join_) != std::string_view::npos) joined_ = true;
    };
    Result<std::unique_ptr<Dispatcher>> created =
        Dispatcher::Create(&context_, options, ConfigToProto(ModelConfig{}));
    if (!created.ok()) Fail(created.status().ToString());
    dispatcher_ = std::move(created).value();
    for (zmq::socket_t* peer : {&worker_, &stranger_}) {
      peer->set(zmq::sockopt::linger, 0);
      peer->connect(dispatcher_->endpoint());
    }
    genome_ = HarnessGenome();
    Refill();
  }

  void Run(const uint8_t* data, size_t size) {
    for (FuzzMessage& message : ParseDispatcherInput(data, size)) {
      if (message.fix_build_id) {
        for (std::string& frame : message.frames) {
          Result<v1::Envelope> envelope = protocol::Decode(frame);
          if (!envelope.ok() || !envelope->has_hello()) continue;
          envelope->mutable_hello()->set_build_id(protocol::BuildId());
          frame = protocol::Encode(*envelope);
        }
      }
      zmq::socket_t& sender = message.stranger ? stranger_ : worker_;
      for (size_t i = 0; i < message.frames.size(); ++i) {
        const bool more = i + 1 < message.frames.size();
        sender.send(zmq::buffer(message.frames[i]),
                    more ? zmq::send_flags::sndmore | zmq::send_flags::dontwait
                         : zmq::send_flags::dontwait);
      }
      Serve(message.wait ? kWaitMs : 0);
      Drain(stranger_);
      Drain(worker_);
    }

    ++hellos_;
    expected_join_ = "worker harness:" + std::to_string(hellos_) + " joined";
    joined_ = false;
    v1::Envelope hello;
    v1::Hello* h = hello.mutable_hello();
    h->set_protocol_version(protocol::kVersion);
    h->set_build_id(protocol::BuildId());
    h->set_threads(2);
    h->set_host("harness");
    h->set_pid(hellos_);
    worker_.send(zmq::buffer(protocol::Encode(hello)),
                 zmq::send_flags::dontwait);

    const auto give_up =
        std::chrono::steady_clock::now() + std::chrono::seconds(5);
    bool welcomed = false;
    for (;;) {
      Serve(0);
      Drain(stranger_);
      welcomed = Drain(worker_) || welcomed;
      if (welcomed && joined_) break;
      if (std::chrono::steady_clock::now() > give_up) {
        Fail("no welcome for a valid hello within 5 s");
      }
    }
    Refill();
  }

 private:
  // Polls the dispatcher once and checks its completions.
  void Serve(int timeout_ms) {
    for (const Completion& c : dispatcher_->Poll(timeout_ms)) {
      if (pending_.erase(c.individual) == 0) {
        Fail("individual " + std::to_string(c.individual) +
             " completed twice or never submitted");
      }
    }
  }

  // Reads everything the dispatcher sent `peer`; true if a Welcome was
  // among it.
  bool Drain(zmq::socket_t& peer) {
    bool welcome = false;
    zmq::message_t frame;
    while (peer.recv(frame, zmq::recv_flags::dontwait)) {
      if (frame.more()) Fail("the dispatcher sent a multi-frame message");
      Result<v1::Envelope> envelope = protocol::Decode(frame.to_string_view());
      if (!envelope.ok()) {
        Fail("the dispatcher sent an undecodable message: " +
             envelope.status().message());
      }
      welcome = welcome || envelope->has_welcome();
    }
    return welcome;
  }

  // Submits again the individuals that completed.
  void Refill() {
    for (uint64_t id = 1; id <= kIndividuals; ++id) {
      if (pending_.insert(id).second) dispatcher_->Submit(id, genome_);
    }
    if (dispatcher_->pending() != pending_.size()) {
      Fail("the dispatcher has " + std::to_string(dispatcher_->pending()) +
           " pending, expected " + std::to_string(pending_.size()));
    }
  }

  zmq::context_t context_{1};
  std::unique_ptr<Dispatcher> dispatcher_;
  zmq::socket_t worker_{context_, zmq::socket_type::dealer};
  zmq::socket_t stranger_{context_, zmq::socket_type::dealer};
  v1::Genome genome_;
  std::set<uint64_t> pending_;
  uint64_t hellos_ = 0;
  std::string expected_join_;
  bool joined_ = false;
};

}  // namespace
}  // namespace animat::fuzz

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  animat::fuzz::QuietProtobufLogs();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  // Never destroyed: it outlives every input and the process's exit.
  static animat::fuzz::Harness* harness = new animat::fuzz::Harness;
  harness->Run(data, size);
  return 0;
}
