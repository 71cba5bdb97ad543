// Point sets for the geometry tests, and gtest printing of edges.
#ifndef ANIMAT_TESTS_GEOMETRY_POINT_SOURCE_H_
#define ANIMAT_TESTS_GEOMETRY_POINT_SOURCE_H_

#include <cstdint>
#include <ostream>
#include <random>
#include <utility>
#include <vector>

#include "common/base/vec2.h"
#include "common/geometry/gabriel.h"

namespace animat {

// Lets gtest print edges in failure messages (found by ADL).
inline void PrintTo(const IndexEdge& e, std::ostream* os) {
  *os << e.a << "-" << e.b;
}

namespace testing {

// Fixed-seed points. The double recipe (53 high bits) is written out so the
// sets are the same with every standard library.
class PointSource {
 public:
  explicit PointSource(uint64_t seed) : engine_(seed) {}

  double Uniform(double lo, double hi) {
    const double u = static_cast<double>(engine_() >> 11) * 0x1.0p-53;
    return lo + (hi - lo) * u;
  }

  std::vector<Vec2> InSquare(int n) {
    std::vector<Vec2> points;
    for (int i = 0; i < n; ++i) {
      points.push_back({Uniform(0, 1), Uniform(0, 1)});
    }
    return points;
  }

  // n distinct points of the integer grid [0, side)^2, in random order:
  // many equal distances and cocircular quadruples.
  std::vector<Vec2> OnGrid(int n, int side) {
    std::vector<Vec2> grid;
    for (int x = 0; x < side; ++x) {
      for (int y = 0; y < side; ++y) {
        grid.push_back({static_cast<double>(x), static_cast<double>(y)});
      }
    }
    for (int i = static_cast<int>(grid.size()) - 1; i > 0; --i) {
      std::swap(grid[i], grid[engine_() % static_cast<uint64_t>(i + 1)]);
    }
    grid.resize(n);
    return grid;
  }

 private:
  std::mt19937_64 engine_;
};

}  // namespace testing
}  // namespace animat

#endif  // ANIMAT_TESTS_GEOMETRY_POINT_SOURCE_H_
