// The master-worker protocol in one place (zguide's mdp.h habit): version,
// timing and size limits, the build id, and encoding and decoding of the
// single-frame Envelope messages (docs/protocol.md). The genome's bytes and
// the fingerprints are genome_wire.h's.
//
// Decoding takes bytes from the network: it never crashes and never
// throws; anything malformed comes back as a Status saying what is wrong.
// All functions are thread-safe.
#ifndef ANIMAT_COMMON_PROTOCOL_PROTOCOL_H_
#define ANIMAT_COMMON_PROTOCOL_PROTOCOL_H_

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "animat/v1/protocol.pb.h"
#include "animat/v1/trace.pb.h"
#include "common/base/status.h"

namespace animat::protocol {

// Bumped on any incompatible change of protocol.proto's meaning.
// 2: Work may carry its configuration (several configurations per master).
inline constexpr uint32_t kVersion = 2;

// The model configurations a worker keeps (Work.config), the least
// recently used forgotten first; a master serves at most this many at
// once, so that a worker never forgets one its master still uses.
inline constexpr size_t kMaxConfigs = 64;

// The version of the model this build implements (docs/model.md §12).
inline constexpr int kModelVersion = 3;

// Default heartbeat interval; a peer silent for kLiveness intervals is
// presumed dead.
inline constexpr int kHeartbeatMs = 1000;
inline constexpr int kLiveness = 3;

// Evaluations are prefetched: a worker asks for threads * kPrefetch.
inline constexpr int kPrefetch = 2;
// A worker may hold threads * kPrefetch * kCreditCapFactor credit.
inline constexpr int kCreditCapFactor = 2;
// Leases of an individual that may end without a result (its worker died
// or the lease expired) before the master evaluates it alone, in a child
// process of its own (DispatcherOptions::isolation).
inline constexpr int kMaxAttempts = 3;

// Worker reconnection backoff after the master goes silent.
inline constexpr int kReconnectMinMs = 100;
inline constexpr int kReconnectMaxMs = 5000;

// ---- Limits: every field of every message (docs/protocol.md, "Limits").
// Decode checks them on both sides: a frame larger than its body may take
// (MaxEnvelopeBytes) is refused before it is parsed, a field out of its
// range after; the reason names the body, the field and the limit.
//
// Strings, in bytes.
inline constexpr size_t kMaxHostBytes = 255;     // Hello.host (a DNS name)
inline constexpr size_t kMaxBuildIdBytes = 256;  // Hello, Welcome.build_id
// Refuse.reason, Goodbye.reason, EvaluationResult.reason (a worker cuts a
// longer reason of its own to this).
inline constexpr size_t kMaxReasonBytes = 1024;
// Numbers, each in [min, max].
// Welcome.heartbeat_ms, and --heartbeat-ms of both programs: kLiveness
// times the most fits an int.
inline constexpr int kMinHeartbeatMs = 10;
inline constexpr int kMaxHeartbeatMs = 600000;
// Hello.threads, in [1, kMaxThreads].
inline constexpr uint32_t kMaxThreads = 65536;
// Hello.pid, in [0, kMaxPid] (a pid_t).
inline constexpr uint64_t kMaxPid = 2147483647;
// Credit.credit, in [1, kMaxCredit]: the most credit the master records
// for the largest worker. Also the most individuals a Goodbye returns.
inline constexpr uint32_t kMaxCredit =
    kMaxThreads * kPrefetch * kCreditCapFactor;
// Every individual (Work, Results, Goodbye, Acknowledge), in
// [0, kMaxIndividual]: the lineage store keeps ids as SQLite integers.
inline constexpr uint64_t kMaxIndividual = 9223372036854775807u;
// Most items in one Work and results in one Results message, and most
// individuals in one Acknowledge.
inline constexpr int kMaxBatch = 256;
inline constexpr int kMaxAcknowledged = 4096;
// EvaluationResult.source_distances: at most the most guidance trials
// (GuidanceConfig.trials).
inline constexpr int kMaxSourceDistances = 64;
// EvaluationResult: status known and not unspecified; fitness present,
// finite and >= 0 (any finite value with source_distances, the guidance
// score) exactly when the status is OK; source_distances only with OK, at
// most kMaxSourceDistances, each finite and >= 0; cells, steps and the
// body's counts >= 0; the body's spreads finite with spread_major >=
// spread_minor >= 0. WorkResult.wall_seconds finite and >= 0.
//
// Whole messages, in bytes. The worker's socket takes up to
// kMaxMessageBytes (a Work); the master's up to kMaxWorkerMessageBytes,
// the most a worker sends (a Goodbye returning kMaxCredit individuals):
// ZeroMQ drops a connection that sends more (ZMQ_MAXMSGSIZE).
inline constexpr int64_t kMaxMessageBytes = 64 << 20;
inline constexpr int64_t kMaxWorkerMessageBytes = 4 << 20;
// Most bytes of items in one Work message (half the limit: genomes of up
// to 10000 elements, about 350 KB each, always fit).
inline constexpr size_t kMaxWorkBytes = kMaxMessageBytes / 2;
// The most bytes of an envelope carrying `body`: 4 KiB for a Hello,
// Refuse, Credit or Heartbeat, 64 KiB for an Acknowledge, 1 MiB for a
// Welcome or Results, kMaxWorkerMessageBytes for a Goodbye,
// kMaxMessageBytes for a Work (and for a frame without a body).
size_t MaxEnvelopeBytes(v1::Envelope::BodyCase body);

// Identifies the simulator build: project version, git commit, compiler and
// target architecture. Workers of another build are refused: they may give
// different bits.
const std::string& BuildId();

// What --version prints, one "name: value" line each (no final newline):
// the build id, the protocol version, the model version and the kernels'
// instruction-set path in use with those this machine supports
// (common/kernels/isa.h).
std::string VersionText();

// Serialises an envelope stamped with kVersion.
std::string Encode(v1::Envelope envelope);

// Parses one frame. Fails, saying why, on bytes that are not an
// Envelope, on a frame larger than its body may take (before parsing it),
// on an envelope with no body or of another protocol version (unless it
// is a Hello, which the master refuses naming both versions, or a Refuse,
// on which the worker gives up), and on a field outside its limits
// (CheckEnvelope).
Result<v1::Envelope> Decode(std::string_view frame);

// The limits above, field by field, for an envelope of this protocol
// version (of another one, the strings only): the first field out of its
// range, e.g. "hello.threads 0 outside [1, 65536]". A Results message's
// results are checked here for their number and individuals only; the
// rest of each one the master checks one by one (CheckWorkResult), so
// that one bad result does not cost the others. Likewise a Work's items
// are checked here for their number only, and each by the worker
// (CheckWorkItem).
Status CheckEnvelope(const v1::Envelope& envelope);

// Item `index` of a Work: its individual within [0, kMaxIndividual], e.g.
// "work.items[1].individual 9223372036854775808 outside [0,
// 9223372036854775807]".
Status CheckWorkItem(const v1::WorkItem& item, int index);

// A result a master may record: a known status other than unspecified,
// a fitness present, finite and >= 0 exactly when the status is OK, a
// reason of at most kMaxReasonBytes, cells and steps >= 0, and, if it
// carries a body summary, counts >= 0 and spreads finite with
// spread_major >= spread_minor >= 0. The message names the first fault.
Status ValidateResult(const v1::EvaluationResult& result);

// ValidateResult, and the individual and wall_seconds of a WorkResult in
// their ranges.
Status CheckWorkResult(const v1::WorkResult& result);

// "hello", "work", ... for log lines; "none" without a body.
const char* BodyName(const v1::Envelope& envelope);
const char* BodyName(v1::Envelope::BodyCase body);

}  // namespace animat::protocol

#endif  // ANIMAT_COMMON_PROTOCOL_PROTOCOL_H_
