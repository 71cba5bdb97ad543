#include "common/kernels/kernels.h"

#include "common/kernels/kernel_paths.h"

namespace animat::kernels {

// Without the wider builds (ANIMAT_KERNELS_X86_PATHS unset) only the
// baseline exists, and IsaSupported() admits no other path.
#ifdef ANIMAT_KERNELS_X86_PATHS
#define ANIMAT_ON_PATH(isa, call) \
  switch (isa) {                  \
    case Isa::kAvx512:            \
      return isa_avx512::call;    \
    case Isa::kAvx2:              \
      return isa_avx2::call;      \
    case Isa::kBaseline:          \
      break;                      \
  }                               \
  return isa_baseline::call
#else
#define ANIMAT_ON_PATH(isa, call) \
  (void)(isa);                    \
  return isa_baseline::call
#endif

void GrnStep(Isa isa, const GrnStepArgs<float>& args) {
  ANIMAT_ON_PATH(isa, GrnStepFloat(args));
}

void GrnStep(Isa isa, const GrnStepArgs<double>& args) {
  ANIMAT_ON_PATH(isa, GrnStepDouble(args));
}

void PairKernels(Isa isa, const PairKernelArgs& args) {
  ANIMAT_ON_PATH(isa, PairKernelsImpl(args));
}

int NearPairs(Isa isa, const NearPairsArgs& args) {
  ANIMAT_ON_PATH(isa, NearPairsImpl(args));
}

bool WithinMove(Isa isa, const WithinMoveArgs& args) {
  ANIMAT_ON_PATH(isa, WithinMoveImpl(args));
}

void VerletPredict(Isa isa, const VerletPredictArgs& args) {
  ANIMAT_ON_PATH(isa, VerletPredictImpl(args));
}

void VerletCorrect(Isa isa, const VerletCorrectArgs& args) {
  ANIMAT_ON_PATH(isa, VerletCorrectImpl(args));
}

#undef ANIMAT_ON_PATH

void GrnStep(const GrnStepArgs<float>& args) { GrnStep(ActiveIsa(), args); }
void GrnStep(const GrnStepArgs<double>& args) { GrnStep(ActiveIsa(), args); }
void PairKernels(const PairKernelArgs& args) { PairKernels(ActiveIsa(), args); }

}  // namespace animat::kernels
