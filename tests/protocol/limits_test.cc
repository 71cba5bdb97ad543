// The protocol's limits (common/protocol/protocol.h): Decode refuses a
// frame larger than its body may take before parsing it, and every field
// outside its range, naming it; a message at its limits passes; results
// are checked one by one by CheckWorkResult.
#include <gtest/gtest.h>

#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "animat/v1/protocol.pb.h"
#include "common/protocol/protocol.h"

namespace animat::protocol {
namespace {

constexpr uint64_t kBeyond = kMaxIndividual + 1;

// Decode's reason for refusing `envelope` (encoded as a peer would), or
// "decoded" when it passes.
std::string Verdict(const v1::Envelope& envelope) {
  Result<v1::Envelope> decoded = Decode(Encode(envelope));
  return decoded.ok() ? "decoded" : decoded.status().message();
}

v1::Envelope Hello(const std::function<void(v1::Hello*)>& edit) {
  v1::Envelope e;
  v1::Hello* h = e.mutable_hello();
  h->set_protocol_version(kVersion);
  h->set_build_id(BuildId());
  h->set_threads(4);
  h->set_host("node17");
  h->set_pid(1234);
  edit(h);
  return e;
}

v1::Envelope Welcome(uint32_t heartbeat_ms) {
  v1::Envelope e;
  e.mutable_welcome()->set_build_id(BuildId());
  e.mutable_welcome()->set_heartbeat_ms(heartbeat_ms);
  return e;
}

TEST(LimitsTest, EveryNumericFieldAtItsLimitsPasses) {
  EXPECT_EQ(Verdict(Hello([](v1::Hello* h) { h->set_threads(1); })), "decoded");
  EXPECT_EQ(Verdict(Hello([](v1::Hello* h) {
              h->set_threads(kMaxThreads);
              h->set_pid(kMaxPid);
              h->set_host(std::string(kMaxHostBytes, 'h'));
              h->set_build_id(std::string(kMaxBuildIdBytes, 'b'));
            })),
            "decoded");
  EXPECT_EQ(Verdict(Welcome(kMinHeartbeatMs)), "decoded");
  EXPECT_EQ(Verdict(Welcome(kMaxHeartbeatMs)), "decoded");
  v1::Envelope credit;
  credit.mutable_credit()->set_credit(kMaxCredit);
  EXPECT_EQ(Verdict(credit), "decoded");
  v1::Envelope work;
  for (int i = 0; i < kMaxBatch; ++i) {
    work.mutable_work()->add_items()->set_individual(kMaxIndividual - i);
  }
  EXPECT_EQ(Verdict(work), "decoded");
  v1::Envelope goodbye;
  for (uint32_t i = 0; i < kMaxCredit; ++i) {
    goodbye.mutable_goodbye()->add_returned(kMaxIndividual - i);
  }
  goodbye.mutable_goodbye()->set_reason(std::string(kMaxReasonBytes, 'r'));
  EXPECT_EQ(Verdict(goodbye), "decoded");
  v1::Envelope acknowledge;
  for (int i = 0; i < kMaxAcknowledged; ++i) {
    acknowledge.mutable_acknowledge()->add_individuals(kMaxIndividual - i);
  }
  EXPECT_EQ(Verdict(acknowledge), "decoded");
  v1::Envelope refuse;
  refuse.mutable_refuse()->set_reason(std::string(kMaxReasonBytes, 'r'));
  EXPECT_EQ(Verdict(refuse), "decoded");
}

TEST(LimitsTest, EveryFieldBeyondItsLimitsIsRefusedByName) {
  v1::Envelope credit_zero;
  credit_zero.mutable_credit()->set_credit(0);
  v1::Envelope credit_beyond;
  credit_beyond.mutable_credit()->set_credit(kMaxCredit + 1);
  v1::Envelope results_beyond;
  results_beyond.mutable_results()->add_results()->set_individual(1);
  results_beyond.mutable_results()->add_results()->set_individual(kBeyond);
  v1::Envelope goodbye_reason;
  goodbye_reason.mutable_goodbye()->set_reason(
      std::string(kMaxReasonBytes + 1, 'r'));
  v1::Envelope refuse_reason;
  refuse_reason.mutable_refuse()->set_reason(
      std::string(kMaxReasonBytes + 1, 'r'));
  v1::Envelope acknowledge_beyond;
  acknowledge_beyond.mutable_acknowledge()->add_individuals(kBeyond);
  v1::Envelope acknowledge_many;
  for (int i = 0; i <= kMaxAcknowledged; ++i) {
    acknowledge_many.mutable_acknowledge()->add_individuals(i);
  }
  v1::Envelope welcome_build = Welcome(1000);
  welcome_build.mutable_welcome()->set_build_id(
      std::string(kMaxBuildIdBytes + 1, 'b'));
  const std::vector<std::pair<v1::Envelope, std::string>> cases = {
      {Hello([](v1::Hello* h) { h->set_threads(0); }),
       "hello.threads 0 outside [1, 65536]"},
      {Hello([](v1::Hello* h) { h->set_threads(kMaxThreads + 1); }),
       "hello.threads 65537 outside [1, 65536]"},
      {Hello([](v1::Hello* h) { h->set_pid(kMaxPid + 1); }),
       "hello.pid 2147483648 outside [0, 2147483647]"},
      {Hello([](v1::Hello* h) {
         h->set_host(std::string(kMaxHostBytes + 1, 'h'));
       }),
       "hello.host of 256 bytes, above the limit of 255"},
      {Hello([](v1::Hello* h) {
         h->set_build_id(std::string(kMaxBuildIdBytes + 1, 'b'));
       }),
       "hello.build_id of 257 bytes, above the limit of 256"},
      {Welcome(0), "welcome.heartbeat_ms 0 outside [10, 600000]"},
      {Welcome(kMaxHeartbeatMs + 1),
       "welcome.heartbeat_ms 600001 outside [10, 600000]"},
      {Welcome(715827883), "welcome.heartbeat_ms 715827883 outside"},
      {welcome_build, "welcome.build_id of 257 bytes"},
      {credit_zero, "credit.credit 0 outside [1, 262144]"},
      {credit_beyond, "credit.credit 262145 outside [1, 262144]"},
      {results_beyond, "results.results[1].individual 9223372036854775808"},
      {goodbye_reason, "goodbye.reason of 1025 bytes, above the limit of 1024"},
      {refuse_reason, "refuse.reason of 1025 bytes, above the limit of 1024"},
      {acknowledge_beyond, "acknowledge.individuals[0] 9223372036854775808"},
      {acknowledge_many,
       "acknowledge.individuals holds 4097, above the limit of 4096"},
  };
  for (const auto& [envelope, reason] : cases) {
    EXPECT_EQ(Verdict(envelope).rfind(reason, 0), 0u)
        << Verdict(envelope) << "\nexpected: " << reason;
  }
}

// A Work decodes whatever its items' individuals: each item is checked on
// its own, so that one out of range does not cost the others.
TEST(LimitsTest, AWorksItemsAreCheckedOneByOne) {
  v1::Envelope work;
  work.mutable_work()->add_items()->set_individual(3);
  work.mutable_work()->add_items()->set_individual(kBeyond);
  work.mutable_work()->add_items()->set_individual(kMaxIndividual);
  EXPECT_EQ(Verdict(work), "decoded");
  EXPECT_TRUE(CheckWorkItem(work.work().items(0), 0).ok());
  EXPECT_EQ(CheckWorkItem(work.work().items(1), 1).message(),
            "work.items[1].individual 9223372036854775808 outside [0, "
            "9223372036854775807]");
  EXPECT_TRUE(CheckWorkItem(work.work().items(2), 2).ok());
}

// A Hello of another protocol version still decodes, its strings bounded
// (for the master's log) but its numbers its own: the master refuses it
// naming both versions.
TEST(LimitsTest, AHelloOfAnotherVersionIsCheckedForItsStringsOnly) {
  v1::Envelope other = Hello([](v1::Hello* h) {
    h->set_protocol_version(kVersion + 1);
    h->set_threads(0);
  });
  other.set_protocol_version(kVersion + 1);
  Result<v1::Envelope> decoded = Decode(other.SerializeAsString());
  ASSERT_TRUE(decoded.ok()) << decoded.status().ToString();
  other.mutable_hello()->set_host(std::string(kMaxHostBytes + 1, 'h'));
  EXPECT_FALSE(Decode(other.SerializeAsString()).ok());
}

TEST(LimitsTest, AFrameLargerThanItsBodyMayTakeIsRefusedBeforeParsing) {
  v1::Envelope hello = Hello([](v1::Hello* h) {
    h->set_host(std::string(16 << 20, 'h'));  // 16 MiB.
  });
  const std::string frame = Encode(hello);
  Result<v1::Envelope> decoded = Decode(frame);
  ASSERT_FALSE(decoded.ok());
  EXPECT_EQ(decoded.status().message(), "a hello of " +
                                            std::to_string(frame.size()) +
                                            " bytes, above the limit of 4096");
  // Unparsed: the same frame with invalid UTF-8 in the host (which a parse
  // would reject as not an Envelope) gets the same answer.
  std::string broken = frame;
  broken[frame.size() - 100] = '\xff';
  ASSERT_FALSE(Decode(broken).ok());
  EXPECT_EQ(Decode(broken).status().message(), decoded.status().message());

  for (const v1::Envelope::BodyCase body :
       {v1::Envelope::kHello, v1::Envelope::kRefuse, v1::Envelope::kCredit,
        v1::Envelope::kHeartbeat}) {
    EXPECT_EQ(MaxEnvelopeBytes(body), 4096u) << BodyName(body);
  }
  EXPECT_EQ(MaxEnvelopeBytes(v1::Envelope::kGoodbye),
            static_cast<size_t>(kMaxWorkerMessageBytes));
  EXPECT_EQ(MaxEnvelopeBytes(v1::Envelope::kWork),
            static_cast<size_t>(kMaxMessageBytes));
  // Every body a worker sends fits the master's socket.
  for (const v1::Envelope::BodyCase body :
       {v1::Envelope::kHello, v1::Envelope::kCredit, v1::Envelope::kResults,
        v1::Envelope::kHeartbeat, v1::Envelope::kGoodbye}) {
    EXPECT_LE(MaxEnvelopeBytes(body),
              static_cast<size_t>(kMaxWorkerMessageBytes))
        << BodyName(body);
  }
  // Garbage that is no protobuf at all is still said to be so.
  EXPECT_EQ(Decode(std::string("\xff\xff\xff", 3)).status().message(),
            "not an animat.v1.Envelope (3 bytes)");
}

TEST(LimitsTest, AResultIsCheckedWithItsWallTimeAndIndividual) {
  v1::WorkResult r;
  r.set_individual(3);
  r.mutable_result()->set_status(v1::EvaluationResult::TOO_FEW_CELLS);
  r.mutable_result()->set_reason("too few");
  r.set_wall_seconds(0.5);
  EXPECT_TRUE(CheckWorkResult(r).ok());
  for (v1::WorkResult::Isa isa :
       {v1::WorkResult::BASELINE, v1::WorkResult::AVX2,
        v1::WorkResult::AVX512}) {
    v1::WorkResult named = r;
    named.set_isa(isa);
    EXPECT_TRUE(CheckWorkResult(named).ok()) << isa;
  }
  const std::vector<
      std::pair<std::function<void(v1::WorkResult*)>, std::string>>
      cases = {
          {[](v1::WorkResult* w) { w->set_individual(kBeyond); },
           "individual 9223372036854775808 outside"},
          {[](v1::WorkResult* w) { w->set_wall_seconds(-0.25); },
           "wall time -0.25"},
          {[](v1::WorkResult* w) {
             w->set_wall_seconds(std::numeric_limits<double>::infinity());
           },
           "wall time inf"},
          {[](v1::WorkResult* w) { w->mutable_result()->set_cells(-1); },
           "cells -1"},
          {[](v1::WorkResult* w) { w->mutable_result()->set_steps(-7); },
           "steps -7"},
          {[](v1::WorkResult* w) {
             w->mutable_result()->set_reason(
                 std::string(kMaxReasonBytes + 1, 'r'));
           },
           "reason of 1025 bytes, above the limit of 1024"},
          {[](v1::WorkResult* w) {
             w->mutable_result()->set_status(v1::EvaluationResult::CRASHED);
             w->mutable_result()->set_fitness(1.0);
           },
           "a fitness without status OK"},
          {[](v1::WorkResult* w) {
             w->set_isa(static_cast<v1::WorkResult::Isa>(7));
           },
           "isa 7 outside [0, 3]"},
      };
  for (const auto& [edit, reason] : cases) {
    v1::WorkResult bad = r;
    edit(&bad);
    const Status status = CheckWorkResult(bad);
    ASSERT_FALSE(status.ok()) << reason;
    EXPECT_EQ(status.message().rfind(reason, 0), 0u) << status.message();
  }
}

}  // namespace
}  // namespace animat::protocol
