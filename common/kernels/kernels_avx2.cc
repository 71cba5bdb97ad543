// The kernels built for the avx2 path (isa.h, kernels_impl.inc).
#define ANIMAT_ISA_NAMESPACE isa_avx2
#include "common/kernels/kernels_impl.inc"
