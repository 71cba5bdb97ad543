// A 2-D vector of doubles with the few operations the model needs.
//
// Plain value type. Every operation is written out so the rounding is the
// same in every build (no fused multiply-add; see docs/model.md).
#ifndef ANIMAT_COMMON_BASE_VEC2_H_
#define ANIMAT_COMMON_BASE_VEC2_H_

#include <cmath>

namespace animat {

struct Vec2 {
  double x = 0.0;
  double y = 0.0;

  constexpr Vec2() = default;
  constexpr Vec2(double x_in, double y_in) : x(x_in), y(y_in) {}

  constexpr Vec2 operator+(Vec2 o) const { return {x + o.x, y + o.y}; }
  constexpr Vec2 operator-(Vec2 o) const { return {x - o.x, y - o.y}; }
  constexpr Vec2 operator-() const { return {-x, -y}; }
  constexpr Vec2 operator*(double s) const { return {x * s, y * s}; }
  constexpr Vec2 operator/(double s) const { return {x / s, y / s}; }
  constexpr Vec2& operator+=(Vec2 o) {
    x += o.x;
    y += o.y;
    return *this;
  }
  constexpr Vec2& operator-=(Vec2 o) {
    x -= o.x;
    y -= o.y;
    return *this;
  }
  constexpr bool operator==(const Vec2&) const = default;
};

constexpr double Dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
// z component of the 3-D cross product: > 0 when b is counter-clockwise
// from a.
constexpr double Cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
// Euclidean length as sqrt(x*x + y*y) (model §2.2: not hypot).
inline double Length(Vec2 a) { return std::sqrt(a.x * a.x + a.y * a.y); }
inline bool IsFinite(Vec2 a) {
  return std::isfinite(a.x) && std::isfinite(a.y);
}

}  // namespace animat

#endif  // ANIMAT_COMMON_BASE_VEC2_H_
