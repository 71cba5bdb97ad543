// libFuzzer target: the lease scheduler (master/dispatch/lease_scheduler.h)
// alone, without a socket. Each input is a script of events, one byte
// choosing each and the next bytes its arguments: a frame of any bytes
// from one of three peers (decoded as the transport would), a valid hello,
// a credit, a result (valid or not) for one of the individuals, time
// passing (housekeeping and dispatch), or one peer's outbox failing or
// recovering. A fresh scheduler and manual clock serve each input, with
// individuals 1..kIndividuals submitted; a completed one is submitted
// again, so there is always work.
//
// Checked: no crash, exception or sanitizer report; every message the
// scheduler sends decodes; an individual completes at most once per
// submission; the scheduler's pending count is ours.
#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "common/base/clock.h"
#include "common/protocol/genome_wire.h"
#include "common/protocol/protocol.h"
#include "fuzz/fuzz_common.h"
#include "master/dispatch/lease_scheduler.h"

namespace animat::fuzz {
namespace {

constexpr uint64_t kIndividuals = 6;
const char* const kPeers[] = {"peer-a", "peer-b", "peer-c"};

[[noreturn]] void Fail(const std::string& what) {
  std::fprintf(stderr, "scheduler_fuzzer: %s\n", what.c_str());
  std::abort();
}

class CheckingOutbox : public Outbox {
 public:
  bool Deliver(const std::string& identity, const std::string& bytes,
               std::string* problem) override {
    if (!protocol::Decode(bytes).ok())
      Fail("sent a message that does not decode");
    if (failing_.count(identity) != 0) {
      *problem = "its queue is full";
      return false;
    }
    return true;
  }
  void Toggle(const std::string& identity) {
    if (failing_.erase(identity) == 0) failing_.insert(identity);
  }

 private:
  std::set<std::string> failing_;
};

protocol::SerializedGenome GenomeOf(uint64_t individual) {
  v1::Genome genome;
  genome.add_elements()->set_x(static_cast<double>(individual));
  return protocol::SerializeGenome(genome);
}

// Reads the script's bytes in order; 0 once they run out.
class Script {
 public:
  Script(const uint8_t* data, size_t size) : data_(data), size_(size) {}
  bool done() const { return at_ >= size_; }
  uint8_t Byte() { return at_ < size_ ? data_[at_++] : 0; }
  std::string_view Bytes(size_t n) {
    n = std::min(n, size_ - std::min(size_, at_));
    const std::string_view bytes(reinterpret_cast<const char*>(data_ + at_), n);
    at_ += n;
    return bytes;
  }

 private:
  const uint8_t* data_;
  size_t size_;
  size_t at_ = 0;
};

void Run(const uint8_t* data, size_t size) {
  ManualClock clock;
  CheckingOutbox outbox;
  SchedulerOptions options;
  options.clock = &clock;
  options.heartbeat_ms = 50;
  options.lease_ms = 200;
  options.log = [](std::string_view) {};
  options.idle_notice_ms = 100;
  LeaseScheduler scheduler(options, v1::Config{}, &outbox);
  for (uint64_t id = 1; id <= kIndividuals; ++id) {
    scheduler.Submit(id, GenomeOf(id));
  }
  std::vector<Completion> done;
  Script script(data, size);
  for (int events = 0; !script.done() && events < 256; ++events) {
    const uint8_t kind = script.Byte() % 7;
    const std::string peer = kPeers[script.Byte() % 3];
    v1::Envelope envelope;
    switch (kind) {
      case 0: {  // Any frame.
        const size_t length = script.Byte();
        Result<v1::Envelope> decoded = protocol::Decode(script.Bytes(length));
        if (decoded.ok()) {
          scheduler.Handle(peer, *decoded, &done);
        } else {
          scheduler.Ignore("a malformed message from " +
                           scheduler.PeerName(peer));
        }
        break;
      }
      case 1: {  // A valid hello.
        v1::Hello* hello = envelope.mutable_hello();
        hello->set_protocol_version(protocol::kVersion);
        hello->set_build_id(protocol::BuildId());
        hello->set_threads(1 + script.Byte() % 4);
        hello->set_host("fuzz");
        hello->set_pid(script.Byte());
        envelope.set_protocol_version(protocol::kVersion);
        scheduler.Handle(peer, envelope, &done);
        break;
      }
      case 2:  // Credit.
        envelope.mutable_credit()->set_credit(1 + script.Byte() % 8);
        scheduler.Handle(peer, envelope, &done);
        break;
      case 3: {  // A result, for an individual known or not.
        const uint64_t id = script.Byte() % (kIndividuals + 2);
        const uint8_t how = script.Byte();
        v1::WorkResult* r = envelope.mutable_results()->add_results();
        r->set_individual(id);
        r->set_genome_hash(how & 1 ? GenomeOf(id).hash : how);
        r->mutable_result()->set_status(v1::EvaluationResult::OK);
        r->mutable_result()->set_fitness(how & 2 ? 1.0 : -1.0);
        scheduler.Handle(peer, envelope, &done);
        break;
      }
      case 4:  // Time passes.
        clock.Advance(std::chrono::milliseconds(script.Byte() * 5));
        scheduler.Housekeep(&done);
        break;
      case 5:
        outbox.Toggle(peer);
        break;
      default: {  // A goodbye handing back what it lists.
        v1::Goodbye* goodbye = envelope.mutable_goodbye();
        goodbye->add_returned(script.Byte() % (kIndividuals + 2));
        scheduler.Handle(peer, envelope, &done);
        break;
      }
    }
    scheduler.Dispatch();
    std::set<uint64_t> completed;
    for (const Completion& c : done) {
      if (c.individual < 1 || c.individual > kIndividuals) {
        Fail("completed an individual never submitted");
      }
      if (!completed.insert(c.individual).second) Fail("completed one twice");
    }
    // Submitted again, so that there is always work.
    for (const uint64_t id : completed) scheduler.Submit(id, GenomeOf(id));
    done.clear();
    if (scheduler.pending() != kIndividuals) {
      Fail("pending " + std::to_string(scheduler.pending()) + ", expected " +
           std::to_string(kIndividuals));
    }
  }
}

}  // namespace
}  // namespace animat::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  animat::fuzz::QuietProtobufLogs();
  animat::fuzz::Run(data, size);
  return 0;
}
