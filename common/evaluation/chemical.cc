#include "common/evaluation/chemical.h"

#include "common/base/fast_math.h"

namespace animat {

Vec2 GuidanceSource(Vec2 start, int trial, int trials, double distance) {
  constexpr double kPi = 3.14159265358979323846;
  double s, c;
  SinCos(2.0 * kPi * (trial + 0.5) / trials, &s, &c);
  return {start.x + distance * c, start.y + distance * s};
}

std::vector<int> SkinCells(const Body& body) {
  std::vector<bool> on_skin(body.nodes(), false);
  for (const IndexEdge& e : body.skin) {
    on_skin[e.a] = true;
    on_skin[e.b] = true;
  }
  std::vector<int> cells;
  for (int c = 0; c < body.nodes(); ++c) {
    if (on_skin[c]) cells.push_back(c);
  }
  return cells;
}

void SenseChemical(Vec2 source, double decay_length,
                   std::span<const int> skin_cells,
                   std::span<const Vec2> position,
                   std::vector<double>* values) {
  values->assign(position.size(), 0.0);
  for (int c : skin_cells) {
    (*values)[c] = Exp(-Length(position[c] - source) / decay_length);
  }
}

}  // namespace animat
