#include "common/physics/edge_geometry.h"

#include <immintrin.h>

#include <cmath>

namespace animat {
namespace {

// The scalar formula, for a last odd edge.
void MeasureOne(Vec2 d, double* length, Vec2* unit) {
  const double l = Length(d);
  *length = l;
  *unit = l > 0.0 ? d / l : Vec2{};
}

}  // namespace

void MeasureEdges(const Vec2* x, const int* a, const int* b, int count,
                  double* length, Vec2* unit) {
  static_assert(sizeof(Vec2) == 2 * sizeof(double));
  int k = 0;
#if defined(__SSE4_1__)  // blendv; hadd is SSE3.
  const __m128d zero = _mm_setzero_pd();
  const __m128d one = _mm_set1_pd(1.0);
  for (; k + 1 < count; k += 2) {
    // (dx, dy) of each edge, as x[b] - x[a].
    const __m128d d0 =
        _mm_sub_pd(_mm_loadu_pd(&x[b[k]].x), _mm_loadu_pd(&x[a[k]].x));
    const __m128d d1 =
        _mm_sub_pd(_mm_loadu_pd(&x[b[k + 1]].x), _mm_loadu_pd(&x[a[k + 1]].x));
    // (dx0 dx0 + dy0 dy0, dx1 dx1 + dy1 dy1): one add of the two products
    // each, as Length() computes them.
    const __m128d l =
        _mm_sqrt_pd(_mm_hadd_pd(_mm_mul_pd(d0, d0), _mm_mul_pd(d1, d1)));
    _mm_storeu_pd(length + k, l);
    // l > 0 (false for NaN); elsewhere divide by 1 and keep (0, 0).
    const __m128d positive = _mm_cmpgt_pd(l, zero);
    const __m128d divisor = _mm_blendv_pd(one, l, positive);
    const __m128d keep0 = _mm_unpacklo_pd(positive, positive);
    const __m128d keep1 = _mm_unpackhi_pd(positive, positive);
    const __m128d u0 =
        _mm_and_pd(_mm_div_pd(d0, _mm_unpacklo_pd(divisor, divisor)), keep0);
    const __m128d u1 =
        _mm_and_pd(_mm_div_pd(d1, _mm_unpackhi_pd(divisor, divisor)), keep1);
    _mm_storeu_pd(&unit[k].x, u0);
    _mm_storeu_pd(&unit[k + 1].x, u1);
  }
#endif
  for (; k < count; ++k) MeasureOne(x[b[k]] - x[a[k]], length + k, unit + k);
}

}  // namespace animat
