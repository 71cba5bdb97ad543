// The instruction-set paths of the vector kernels (common/kernels), chosen
// at run time.
//
// Every kernel is compiled once per path: kBaseline at the build's
// architecture (x86-64-v2 by default), kAvx2 with AVX2 as well and kAvx512
// with AVX-512 (F, BW, CD, DQ, VL; 512-bit vectors preferred), all with
// -ffp-contract=off, so never a fused multiply-add.
// Each path does the same IEEE operations in the same order for every
// cell; only how many cells share one instruction differs. So every path
// gives the same bits, which tests/kernels checks on every path the machine
// has.
//
// The path in use is the widest that this build has and this machine
// supports, unless the environment variable ANIMAT_ISA names a narrower one
// ("baseline", "avx2", "avx512"). Thread-safe: the choice is made once, at
// the first call of ActiveIsa(); SelectIsa changes it (for tests).
#ifndef ANIMAT_COMMON_KERNELS_ISA_H_
#define ANIMAT_COMMON_KERNELS_ISA_H_

#include <string>
#include <string_view>
#include <vector>

#include "common/base/status.h"

namespace animat {

enum class Isa { kBaseline, kAvx2, kAvx512 };

// "baseline", "avx2", "avx512".
const char* IsaName(Isa isa);
// The path named `name`; an error lists the names.
Result<Isa> ParseIsa(std::string_view name);

// True when this build has the path and this machine (CPU and operating
// system) can run it. kBaseline always.
bool IsaSupported(Isa isa);
// The supported paths, narrowest first.
std::vector<Isa> SupportedIsas();

// The path named by ANIMAT_ISA, or the widest supported one when the
// variable is unset or empty. Fails, saying why, when it names no path or
// one this machine or build cannot run; programs check it at start-up.
Result<Isa> IsaFromEnvironment();

// The path the kernels use. At the first call: IsaFromEnvironment(), or the
// widest supported path when that fails.
Isa ActiveIsa();
// Makes `isa` the path in use; refuses an unsupported one. Not meant to be
// called while kernels run on other threads (their calls may take either
// path, with the same bits).
Status SelectIsa(Isa isa);

// "avx512 (this machine: baseline, avx2, avx512)": the path in use and the
// supported ones, for --version and logs.
std::string IsaReport();

}  // namespace animat

#endif  // ANIMAT_COMMON_KERNELS_ISA_H_
