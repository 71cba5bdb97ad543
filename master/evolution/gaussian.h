// Normal deviates for the coordinate mutation, by the Box-Muller
// transform written out: only +, -, *, /, sqrt and bit operations (through
// common/base/fast_math.h's SinCos and the logarithm below), so the same
// stream gives the same bits with any C or C++ library (docs/model.md,
// "Determinism"; no <random> distributions, no libm log). Pure functions;
// thread-safe.
#ifndef ANIMAT_MASTER_EVOLUTION_GAUSSIAN_H_
#define ANIMAT_MASTER_EVOLUTION_GAUSSIAN_H_

#include "common/base/rng.h"

namespace animat {

// Natural logarithm of a positive, finite, normal double (fdlibm's
// reduction with a Taylor series; within 1 ulp of libm's, tested).
// Precondition: x is such a double.
double LogPositive(double x);

// Two independent standard normal deviates from two draws of `stream`:
// u1 = 1 - NextDouble() in (0, 1], u2 = NextDouble();
// r = sqrt(-2 ln u1); *z0 = r cos(2 pi u2), *z1 = r sin(2 pi u2).
// |z| < 8.6 (u1 >= 2^-53).
void StandardNormalPair(RandomStream& stream, double* z0, double* z1);

}  // namespace animat

#endif  // ANIMAT_MASTER_EVOLUTION_GAUSSIAN_H_
