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
inline constexpr uint32_t kVersion = 1;

// The version of the model this build implements (docs/model.md §12).
inline constexpr int kModelVersion = 2;

// Default heartbeat interval; a peer silent for kLiveness intervals is
// presumed dead.
inline constexpr int kHeartbeatMs = 1000;
inline constexpr int kLiveness = 3;

// Sockets refuse messages larger than this (ZMQ_MAXMSGSIZE).
inline constexpr int64_t kMaxMessageBytes = 64 << 20;
// Most items in one Work or Results message, and most bytes of items in one
// Work message (half the limit: genomes of up to 10000 elements, about
// 350 KB each, always fit).
inline constexpr int kMaxBatch = 256;
inline constexpr size_t kMaxWorkBytes = kMaxMessageBytes / 2;
// A worker may hold threads * kPrefetch * kCreditCapFactor credit, and may
// claim at most kMaxThreads threads.
inline constexpr int kCreditCapFactor = 2;
inline constexpr uint32_t kMaxThreads = 65536;
// Evaluations are prefetched: a worker asks for threads * kPrefetch.
inline constexpr int kPrefetch = 2;
// An individual whose evaluation killed a worker or timed out this many
// times is recorded as failed instead of retried.
inline constexpr int kMaxAttempts = 3;

// Worker reconnection backoff after the master goes silent.
inline constexpr int kReconnectMinMs = 100;
inline constexpr int kReconnectMaxMs = 5000;

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

// Parses one frame. Fails on bytes that are not an Envelope, on an
// envelope with no body, and on an envelope of another protocol version
// unless it is a Hello (the master refuses it, naming both versions) or a
// Refuse (the worker gives up).
Result<v1::Envelope> Decode(std::string_view frame);

// A result a master may record: a known status other than unspecified,
// a fitness present, finite and >= 0 exactly when the status is OK, and,
// if it carries a body summary, counts >= 0 and spreads finite with
// spread_major >= spread_minor >= 0. The message names the first fault.
Status ValidateResult(const v1::EvaluationResult& result);

// "hello", "work", ... for log lines; "none" without a body.
const char* BodyName(const v1::Envelope& envelope);

}  // namespace animat::protocol

#endif  // ANIMAT_COMMON_PROTOCOL_PROTOCOL_H_
