#include "common/kernels/isa.h"

#include <atomic>
#include <cstdlib>

namespace animat {
namespace {

// Set by CMake when the kernels are also built for x86-64-v3 and -v4.
#ifdef ANIMAT_KERNELS_X86_PATHS
constexpr bool kHasX86Paths = true;
#else
constexpr bool kHasX86Paths = false;
#endif

constexpr Isa kAll[] = {Isa::kBaseline, Isa::kAvx2, Isa::kAvx512};

bool CpuRuns(Isa isa) {
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
  // The extensions the paths are compiled with (common/kernels/
  // CMakeLists.txt). GCC's and Clang's checks include the operating
  // system's support of the wider registers (XCR0). Every AVX-512 machine
  // has FMA, which Clang's -mavx512f implies (it is never used:
  // -ffp-contract=off).
  switch (isa) {
    case Isa::kBaseline:
      return true;
    case Isa::kAvx2:
      return __builtin_cpu_supports("avx2");
    case Isa::kAvx512:
      return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") &&
             __builtin_cpu_supports("avx512f") &&
             __builtin_cpu_supports("avx512bw") &&
             __builtin_cpu_supports("avx512cd") &&
             __builtin_cpu_supports("avx512dq") &&
             __builtin_cpu_supports("avx512vl");
  }
  return false;
#else
  return isa == Isa::kBaseline;
#endif
}

// "baseline, avx2, avx512": the supported paths (SupportedIsas).
std::string SupportedNames() {
  std::string names;
  for (Isa isa : SupportedIsas()) {
    if (!names.empty()) names.append(", ");
    names.append(IsaName(isa));
  }
  return names;
}

// -1 until the first ActiveIsa().
std::atomic<int> g_active{-1};

}  // namespace

const char* IsaName(Isa isa) {
  switch (isa) {
    case Isa::kBaseline:
      return "baseline";
    case Isa::kAvx2:
      return "avx2";
    case Isa::kAvx512:
      return "avx512";
  }
  return "?";
}

Result<Isa> ParseIsa(std::string_view name) {
  for (Isa isa : kAll) {
    if (name == IsaName(isa)) return isa;
  }
  std::string message = "\"";
  message.append(name).append(
      "\" is not an instruction-set path (expected baseline, avx2 or "
      "avx512)");
  return Status::InvalidArgument(message);
}

bool IsaSupported(Isa isa) {
  if (isa != Isa::kBaseline && !kHasX86Paths) return false;
  return CpuRuns(isa);
}

std::vector<Isa> SupportedIsas() {
  std::vector<Isa> supported;
  for (Isa isa : kAll) {
    if (IsaSupported(isa)) supported.push_back(isa);
  }
  return supported;
}

Result<Isa> IsaFromEnvironment() {
  const char* value = std::getenv("ANIMAT_ISA");
  if (value == nullptr || *value == '\0') return SupportedIsas().back();
  Result<Isa> isa = ParseIsa(value);
  if (!isa.ok()) return isa.status().WithPrefix("ANIMAT_ISA");
  if (!IsaSupported(*isa)) {
    std::string message = "ANIMAT_ISA: ";
    message.append(IsaName(*isa));
    message.append(kHasX86Paths ? " is not supported by this machine"
                                : " is not supported by this build");
    message.append(" (supported: ").append(SupportedNames()).append(")");
    return Status::InvalidArgument(message);
  }
  return isa;
}

Isa ActiveIsa() {
  int active = g_active.load(std::memory_order_relaxed);
  if (active < 0) {
    Result<Isa> chosen = IsaFromEnvironment();
    const Isa isa = chosen.ok() ? *chosen : SupportedIsas().back();
    int expected = -1;
    g_active.compare_exchange_strong(expected, static_cast<int>(isa));
    active = g_active.load(std::memory_order_relaxed);
  }
  return static_cast<Isa>(active);
}

Status SelectIsa(Isa isa) {
  if (!IsaSupported(isa)) {
    std::string message = IsaName(isa);
    message.append(" is not supported here");
    return Status::InvalidArgument(message);
  }
  g_active.store(static_cast<int>(isa), std::memory_order_relaxed);
  return Status::Ok();
}

std::string IsaReport() {
  return std::string(IsaName(ActiveIsa())) +
         " (this machine: " + SupportedNames() + ")";
}

}  // namespace animat
