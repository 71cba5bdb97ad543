// The kernels built for the baseline path (isa.h, kernels_impl.inc).
#define ANIMAT_ISA_NAMESPACE isa_baseline
#include "common/kernels/kernels_impl.inc"
