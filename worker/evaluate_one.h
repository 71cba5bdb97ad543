// animat-worker --evaluate-one REQUEST --result RESULT: the evaluation of
// one genome alone, in a process of its own, that a master runs when a
// genome's leases keep ending without a result (docs/protocol.md,
// "Attempts and isolation"). REQUEST holds an animat.v1.IsolatedEvaluation
// (binary); the WorkResult goes, binary, to RESULT.
//
// Runs on the calling thread. A crash of the evaluation is the process's
// (that is the point: the master watches how the process ends).
#ifndef ANIMAT_WORKER_EVALUATE_ONE_H_
#define ANIMAT_WORKER_EVALUATE_ONE_H_

#include <string>

#include "common/base/log.h"

namespace animat {

// Exit codes of EvaluateOne.
inline constexpr int kEvaluatedOne = 0;  // RESULT written.
// The request could not be read, was not this build's (another build may
// give other bits), or its configuration or item is out of bounds; or
// RESULT could not be written. Nothing was evaluated.
inline constexpr int kCannotEvaluateOne = 2;

// Evaluates the request at `request_path` and writes the result to
// `result_path`; says why on `log` when it cannot. Returns an exit code.
int EvaluateOne(const std::string& request_path, const std::string& result_path,
                const LogSink& log);

}  // namespace animat

#endif  // ANIMAT_WORKER_EVALUATE_ONE_H_
