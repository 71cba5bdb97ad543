// The limits of protocol.h, checked field by field (docs/protocol.md,
// "Limits").
#include <cmath>
#include <string>
#include <tuple>
#include <utility>

#include "common/base/text.h"
#include "common/protocol/protocol.h"

namespace animat::protocol {
namespace {

constexpr size_t kSmallMessageBytes = 4 << 10;
constexpr size_t kAcknowledgeBytes = 64 << 10;
constexpr size_t kMediumMessageBytes = 1 << 20;

// The largest a WorkResult can be within the limits (every field at its
// largest, with tags and lengths), so a Results message within them fits
// kMediumMessageBytes.
static_assert(kMaxBatch * (kMaxReasonBytes + 128) + 16 <= kMediumMessageBytes);
// A Goodbye returning kMaxCredit individuals (at most 9 bytes each below
// 2^63, as a packed varint) fits the master's socket.
static_assert(kMaxCredit * 9 + kMaxReasonBytes + 32 <=
              static_cast<uint64_t>(kMaxWorkerMessageBytes));

Status TooLong(const std::string& field, size_t bytes, size_t limit) {
  return Status::InvalidArgument(field + " of " + std::to_string(bytes) +
                                 " bytes, above the limit of " +
                                 std::to_string(limit));
}

Status CheckString(const std::string& field, const std::string& value,
                   size_t limit) {
  return value.size() > limit ? TooLong(field, value.size(), limit)
                              : Status::Ok();
}

Status OutOfRange(const std::string& field, const std::string& value,
                  const std::string& range) {
  return Status::InvalidArgument(field + " " + value + " outside " + range);
}

Status CheckRange(const std::string& field, uint64_t value, uint64_t min,
                  uint64_t max) {
  if (value >= min && value <= max) return Status::Ok();
  std::string range = "[";
  range += std::to_string(min);
  range += ", ";
  range += std::to_string(max);
  range += "]";
  return OutOfRange(field, std::to_string(value), range);
}

template <typename List>
Status CheckCount(const std::string& field, const List& list, int limit) {
  if (list.size() <= limit) return Status::Ok();
  return Status::InvalidArgument(
      field + " holds " + std::to_string(list.size()) +
      ", above the limit of " + std::to_string(limit));
}

// `ids` (a repeated uint64 of individuals): at most `limit`, each in range.
template <typename List>
Status CheckIndividuals(const std::string& field, const List& ids, int limit) {
  Status status = CheckCount(field, ids, limit);
  for (int i = 0; status.ok() && i < ids.size(); ++i) {
    status = CheckRange(field + "[" + std::to_string(i) + "]", ids.Get(i), 0,
                        kMaxIndividual);
  }
  return status;
}

Status CheckHello(const v1::Hello& h, bool this_version) {
  Status status = CheckString("hello.build_id", h.build_id(), kMaxBuildIdBytes);
  if (status.ok()) status = CheckString("hello.host", h.host(), kMaxHostBytes);
  if (!status.ok() || !this_version) return status;
  status = CheckRange("hello.threads", h.threads(), 1, kMaxThreads);
  if (status.ok()) status = CheckRange("hello.pid", h.pid(), 0, kMaxPid);
  return status;
}

Status CheckWelcome(const v1::Welcome& w) {
  Status status =
      CheckString("welcome.build_id", w.build_id(), kMaxBuildIdBytes);
  if (!status.ok()) return status;
  return CheckRange("welcome.heartbeat_ms", w.heartbeat_ms(), kMinHeartbeatMs,
                    kMaxHeartbeatMs);
}

// The items one by one are the worker's to check (CheckWorkItem), so that
// one bad item does not cost the others; but not their number.
Status CheckWork(const v1::Work& work) {
  return CheckCount("work.items", work.items(), kMaxBatch);
}

// The results one by one are the master's to check (CheckWorkResult), so
// that one bad result does not cost the others; but not their number, nor
// an individual no store could hold.
Status CheckResults(const v1::Results& results) {
  Status status = CheckCount("results.results", results.results(), kMaxBatch);
  for (int i = 0; status.ok() && i < results.results_size(); ++i) {
    status = CheckRange("results.results[" + std::to_string(i) + "].individual",
                        results.results(i).individual(), 0, kMaxIndividual);
  }
  return status;
}

Status CheckGoodbye(const v1::Goodbye& g) {
  Status status =
      CheckIndividuals("goodbye.returned", g.returned(), kMaxCredit);
  if (!status.ok()) return status;
  return CheckString("goodbye.reason", g.reason(), kMaxReasonBytes);
}

}  // namespace

Status CheckWorkItem(const v1::WorkItem& item, int index) {
  return CheckRange("work.items[" + std::to_string(index) + "].individual",
                    item.individual(), 0, kMaxIndividual);
}

size_t MaxEnvelopeBytes(v1::Envelope::BodyCase body) {
  switch (body) {
    case v1::Envelope::kHello:
    case v1::Envelope::kRefuse:
    case v1::Envelope::kCredit:
    case v1::Envelope::kHeartbeat:
      return kSmallMessageBytes;
    case v1::Envelope::kAcknowledge:
      return kAcknowledgeBytes;
    case v1::Envelope::kWelcome:
    case v1::Envelope::kResults:
      return kMediumMessageBytes;
    case v1::Envelope::kGoodbye:
      return static_cast<size_t>(kMaxWorkerMessageBytes);
    case v1::Envelope::kWork:
    case v1::Envelope::BODY_NOT_SET:
      break;
  }
  return static_cast<size_t>(kMaxMessageBytes);
}

Status CheckEnvelope(const v1::Envelope& e) {
  const bool this_version = e.protocol_version() == kVersion;
  switch (e.body_case()) {
    case v1::Envelope::kHello:
      return CheckHello(e.hello(), this_version);
    case v1::Envelope::kWelcome:
      return CheckWelcome(e.welcome());
    case v1::Envelope::kRefuse:
      return CheckString("refuse.reason", e.refuse().reason(), kMaxReasonBytes);
    case v1::Envelope::kCredit:
      return CheckRange("credit.credit", e.credit().credit(), 1, kMaxCredit);
    case v1::Envelope::kWork:
      return CheckWork(e.work());
    case v1::Envelope::kResults:
      return CheckResults(e.results());
    case v1::Envelope::kGoodbye:
      return CheckGoodbye(e.goodbye());
    case v1::Envelope::kAcknowledge:
      return CheckIndividuals("acknowledge.individuals",
                              e.acknowledge().individuals(), kMaxAcknowledged);
    case v1::Envelope::kHeartbeat:
    case v1::Envelope::BODY_NOT_SET:
      break;
  }
  return Status::Ok();
}

namespace {

// The status, and the fitness and guidance distances it allows.
Status CheckStatusAndFitness(const v1::EvaluationResult& r) {
  if (!v1::EvaluationResult::Status_IsValid(r.status()) ||
      r.status() == v1::EvaluationResult::STATUS_UNSPECIFIED) {
    return Status::InvalidArgument("unknown status " +
                                   std::to_string(r.status()));
  }
  const bool ok = r.status() == v1::EvaluationResult::OK;
  if (ok != r.has_fitness()) {
    return Status::InvalidArgument(ok ? "status OK without a fitness"
                                      : "a fitness without status OK");
  }
  // A guidance score (model §10.2) is negative when the animat ends
  // farther from the sources than it started.
  const bool guidance = r.source_distances_size() > 0;
  if (ok && !(std::isfinite(r.fitness()) && (guidance || r.fitness() >= 0.0))) {
    return Status::InvalidArgument("fitness " + ShortestDouble(r.fitness()));
  }
  if (guidance && !ok) {
    return Status::InvalidArgument("source distances without status OK");
  }
  if (r.source_distances_size() > kMaxSourceDistances) {
    return Status::InvalidArgument(std::to_string(r.source_distances_size()) +
                                   " source distances, more than " +
                                   std::to_string(kMaxSourceDistances));
  }
  for (double d : r.source_distances()) {
    if (!(std::isfinite(d) && d >= 0.0)) {
      return Status::InvalidArgument("source distance " + ShortestDouble(d));
    }
  }
  return Status::Ok();
}

// The distance swum, the energy and the deepest unjoined overlap.
Status CheckMeasures(const v1::EvaluationResult& r) {
  const bool ok = r.status() == v1::EvaluationResult::OK;
  // The distance swum and the energy: optional, only with status OK,
  // finite and never negative.
  const std::tuple<const char*, bool, double> measures[] = {
      {"distance", r.has_distance(), r.distance()},
      {"energy", r.has_energy(), r.energy()}};
  for (const auto& [name, has, value] : measures) {
    if (has && !ok) {
      return Status::InvalidArgument(std::string(name) +
                                     " present without status OK");
    }
    if (has && !(std::isfinite(value) && value >= 0.0)) {
      return Status::InvalidArgument(std::string(name) + " " +
                                     ShortestDouble(value));
    }
  }
  // The deepest unjoined overlap (model §8.6): a share of r_i + r_j.
  if (r.has_max_overlap() && !ok) {
    return Status::InvalidArgument("max_overlap present without status OK");
  }
  if (r.has_max_overlap() &&
      !(std::isfinite(r.max_overlap()) && r.max_overlap() >= 0.0 &&
        r.max_overlap() <= 1.0)) {
    return Status::InvalidArgument(
        "max_overlap " + ShortestDouble(r.max_overlap()) + " outside [0, 1]");
  }
  return Status::Ok();
}

// The body's counts and spreads.
Status CheckBody(const v1::BodySummary& b) {
  const std::pair<const char*, int32_t> counts[] = {
      {"cells", b.cells()},
      {"springs", b.springs()},
      {"chambers", b.chambers()},
      {"skin_edges", b.skin_edges()}};
  for (const auto& [name, count] : counts) {
    if (count < 0) {
      return Status::InvalidArgument(std::string("body ") + name + " " +
                                     std::to_string(count));
    }
  }
  const std::pair<const char*, double> spreads[] = {
      {"spread_major", b.spread_major()}, {"spread_minor", b.spread_minor()}};
  for (const auto& [name, spread] : spreads) {
    if (!(std::isfinite(spread) && spread >= 0.0)) {
      return Status::InvalidArgument(std::string("body ") + name + " " +
                                     ShortestDouble(spread));
    }
  }
  if (b.spread_minor() > b.spread_major()) {
    return Status::InvalidArgument(
        "body spread_minor " + ShortestDouble(b.spread_minor()) +
        " above spread_major " + ShortestDouble(b.spread_major()));
  }
  return Status::Ok();
}

}  // namespace

Status ValidateResult(const v1::EvaluationResult& r) {
  Status status = CheckStatusAndFitness(r);
  if (status.ok()) status = CheckMeasures(r);
  if (status.ok()) status = CheckString("reason", r.reason(), kMaxReasonBytes);
  if (!status.ok()) return status;
  if (r.cells() < 0) {
    return Status::InvalidArgument("cells " + std::to_string(r.cells()));
  }
  if (r.steps() < 0) {
    return Status::InvalidArgument("steps " + std::to_string(r.steps()));
  }
  return r.has_body() ? CheckBody(r.body()) : Status::Ok();
}

Status CheckWorkResult(const v1::WorkResult& r) {
  Status status = CheckRange("individual", r.individual(), 0, kMaxIndividual);
  if (status.ok()) status = ValidateResult(r.result());
  if (status.ok() &&
      !(std::isfinite(r.wall_seconds()) && r.wall_seconds() >= 0.0)) {
    status = Status::InvalidArgument("wall time " +
                                     ShortestDouble(r.wall_seconds()));
  }
  if (status.ok() && !v1::WorkResult::Isa_IsValid(r.isa())) {
    status = OutOfRange("isa", std::to_string(r.isa()), "[0, 3]");
  }
  return status;
}

}  // namespace animat::protocol
