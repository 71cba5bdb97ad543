// The kernels built for the avx512 path (isa.h, kernels_impl.inc).
#define ANIMAT_ISA_NAMESPACE isa_avx512
#include "common/kernels/kernels_impl.inc"
