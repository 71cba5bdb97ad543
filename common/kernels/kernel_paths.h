// The entry points of each instruction-set path's build of the kernels
// (kernels_impl.inc), for the dispatch in kernels.cc. Internal to
// common/kernels.
#ifndef ANIMAT_COMMON_KERNELS_KERNEL_PATHS_H_
#define ANIMAT_COMMON_KERNELS_KERNEL_PATHS_H_

#include "common/kernels/kernels.h"

#define ANIMAT_DECLARE_KERNEL_PATH(path)                 \
  namespace animat::kernels::path {                      \
  void GrnStepFloat(const GrnStepArgs<float>& args);     \
  void GrnStepDouble(const GrnStepArgs<double>& args);   \
  void PairKernelsImpl(const PairKernelArgs& args);      \
  int NearPairsImpl(const NearPairsArgs& args);          \
  bool WithinMoveImpl(const WithinMoveArgs& args);       \
  void VerletPredictImpl(const VerletPredictArgs& args); \
  void VerletCorrectImpl(const VerletCorrectArgs& args); \
  }

ANIMAT_DECLARE_KERNEL_PATH(isa_baseline)
ANIMAT_DECLARE_KERNEL_PATH(isa_avx2)
ANIMAT_DECLARE_KERNEL_PATH(isa_avx512)

#undef ANIMAT_DECLARE_KERNEL_PATH

#endif  // ANIMAT_COMMON_KERNELS_KERNEL_PATHS_H_
