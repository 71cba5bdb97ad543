#include "common/base/fast_math.h"

namespace animat {

void ExpInPlace(double* values, size_t n) {
  for (size_t i = 0; i < n; ++i) values[i] = Exp(values[i]);
}

void TanhInPlace(double* values, size_t n) {
  for (size_t i = 0; i < n; ++i) values[i] = Tanh(values[i]);
}

void TanhInPlace(float* values, size_t n) {
  for (size_t i = 0; i < n; ++i) values[i] = TanhF(values[i]);
}

}  // namespace animat
