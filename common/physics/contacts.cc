#include "common/physics/contacts.h"

#include <cassert>
#include <cmath>

namespace animat {
namespace {

// The skin of the pair lists (radii; ContactPairs): a cell may move 0.45
// of it before a list is rebuilt. Chosen by measurement
// (docs/benchmarks.md, "Contacts").
constexpr double kSkin = 0.5;

// Contacts act while d < 1 · (r_i + r_j).
constexpr double kRange = 1.0;

// Overlap δ = s − l of a pair at distance² d2 and radius sum s, or a
// value <= 0 when the pair cannot overlap. The square root is taken only
// for pairs within ContactPairs::Reach of overlapping (a relative margin of
// 1e-9 on squared distances), so every pair near s gets the exact test
// δ > 0 on l = sqrt(d2).
double Overlap(double d2, double s, double* length) {
  const double reach = ContactPairs::Reach(kRange, s);
  if (d2 > reach * reach) return 0.0;
  *length = std::sqrt(d2);
  return s - *length;
}

}  // namespace

Contacts::Contacts(const Body& body, const PhysicsParams& params, bool forces)
    : radius_(body.radius),
      stiffness_(params.contact_stiffness),
      damping_(params.contact_damping),
      active_(forces && params.contact_rule != ContactRule::kNone),
      unjoined_(kSkin),
      all_(kSkin),
      near_(kSkin),
      forces_use_all_(params.contact_rule == ContactRule::kAll) {
  radius_.resize(body.nodes(), 1.0);  // A body without radii: all 1.
  std::vector<IndexEdge> joined;
  joined.reserve(body.springs.size());
  for (const Spring& s : body.springs) joined.push_back({s.a, s.b});
  unjoined_.Exclude(joined);
  if (!forces_use_all_) near_.Exclude(joined);
}

void Contacts::AddForces(std::span<const Vec2> x, std::span<const Vec2> v,
                         Vec2* force) {
  if (!active_) return;
  assert(x.size() == radius_.size() && v.size() == radius_.size());
  ContactPairs& pairs = forces_use_all_ ? all_ : unjoined_;
  pairs.Update(x, radius_, kRange);
  if (pairs.moves() != touching_moves_) FindTouching(x, pairs);
  for (const Touch& t : touching_) {
    const double w = -Dot(v[t.j] - v[t.i], t.u);
    const double f = stiffness_ * t.delta + damping_ * w;
    if (!(f > 0.0)) continue;  // Contacts push, never pull.
    const Vec2 fu = t.u * f;
    force[t.j] += fu;
    force[t.i] -= fu;
  }
}

void Contacts::FindTouching(std::span<const Vec2> x,
                            const ContactPairs& pairs) {
  touching_.clear();
  const int n = static_cast<int>(radius_.size());
  for (int i = 0; i < n; ++i) {
    for (int j : pairs.Partners(i)) {
      const Vec2 d = x[j] - x[i];
      const double s = radius_[i] + radius_[j];
      double l = 0.0;
      const double delta = Overlap(d.x * d.x + d.y * d.y, s, &l);
      if (!(delta > 0.0)) continue;
      const Vec2 u = l > 0.0 ? d / l : Vec2{};
      touching_.push_back({i, j, u, delta, s});
    }
  }
  touching_moves_ = pairs.moves();
}

bool Contacts::Near(std::span<const Vec2> x, double margin) {
  if (!active_) return false;
  assert(x.size() == radius_.size());
  const double range = kRange * (1.0 + margin);
  near_.Update(x, radius_, range);
  const int n = static_cast<int>(radius_.size());
  for (int i = 0; i < n; ++i) {
    for (int j : near_.Partners(i)) {
      const Vec2 d = x[j] - x[i];
      const double reach = range * (radius_[i] + radius_[j]);
      if (d.x * d.x + d.y * d.y < reach * reach) return true;
    }
  }
  return false;
}

double Contacts::DeepestUnjoinedOverlap(std::span<const Vec2> x) {
  assert(x.size() == radius_.size());
  unjoined_.Update(x, radius_, kRange);
  double deepest = 0.0;
  if (active_ && !forces_use_all_) {
    // The forces' overlapping pairs are these positions' unjoined ones.
    if (unjoined_.moves() != touching_moves_) FindTouching(x, unjoined_);
    for (const Touch& t : touching_) {
      const double depth = t.delta / t.s;
      if (depth > deepest) deepest = depth;
    }
    return deepest;
  }
  const int n = static_cast<int>(radius_.size());
  for (int i = 0; i < n; ++i) {
    for (int j : unjoined_.Partners(i)) {
      const Vec2 d = x[j] - x[i];
      const double s = radius_[i] + radius_[j];
      double l = 0.0;
      const double delta = Overlap(d.x * d.x + d.y * d.y, s, &l);
      if (!(delta > 0.0)) continue;
      const double depth = delta / s;
      if (depth > deepest) deepest = depth;
    }
  }
  return deepest;
}

}  // namespace animat
