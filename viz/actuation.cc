#include "viz/actuation.h"

#include <algorithm>
#include <cmath>
#include <iterator>

namespace animat::viz {

char ActuationCode(Actuation actuation) {
  switch (actuation) {
    case Actuation::kExpanding:
      return 'e';
    case Actuation::kContracting:
      return 'c';
    case Actuation::kNeutral:
      break;
  }
  return 'n';
}

int StepsBetween(const v1::MotionFrame& previous,
                 const v1::MotionFrame& current) {
  if (previous.phase() == current.phase()) {
    return current.step() - previous.step();
  }
  return std::max(1, current.step());
}

std::vector<Actuation> ClassifyActuation(const v1::MotionFrame* previous,
                                         const v1::MotionFrame& current,
                                         double neutral_rate) {
  const int nodes = current.x_size();
  std::vector<Actuation> out(nodes, Actuation::kNeutral);
  if (previous == nullptr) return out;
  const int steps = StepsBetween(*previous, current);
  if (steps < 1) return out;
  for (int i = 0; i < nodes; ++i) {
    if (i >= current.expand_size() || i >= current.contract_size() ||
        i >= previous->expand_size() || i >= previous->contract_size()) {
      break;
    }
    const double values[] = {current.expand(i), current.contract(i),
                             previous->expand(i), previous->contract(i)};
    if (!std::all_of(std::begin(values), std::end(values),
                     [](double v) { return std::isfinite(v); })) {
      continue;
    }
    const double rate =
        ((values[0] - values[1]) - (values[2] - values[3])) / steps;
    if (std::abs(rate) < neutral_rate) continue;
    out[i] = rate > 0 ? Actuation::kExpanding : Actuation::kContracting;
  }
  return out;
}

}  // namespace animat::viz
