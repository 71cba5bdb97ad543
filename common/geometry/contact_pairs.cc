#include "common/geometry/contact_pairs.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>

#include "common/kernels/kernels.h"

namespace animat {
namespace {

// Coordinates below this magnitude (radii) have an absolute rounding
// error below 2^20 · 2^-53 ≈ 1e-10, far below the margin left by the skin.
constexpr double kBound = 0x1p20;

// A cell may move this fraction of the skin before the list is rebuilt.
// Two cells then close in by at most 0.9 skin, so a pair left out stays
// at least 0.1 skin beyond its reach, whatever the rounding of positions
// and distances below kBound.
constexpr double kMoveFraction = 0.45;

// Each row of the pairs' bounds holds a multiple of this many pairs (the
// widest vector of kernels::NearPairs), padded with pairs never listed, so
// that no row ends in a partial vector.
constexpr size_t kRowPad = 8;

bool InBounds(Vec2 x) {
  // False for NaN and infinities too.
  return std::fabs(x.x) < kBound && std::fabs(x.y) < kBound;
}

}  // namespace

ContactPairs::ContactPairs(double skin) : skin_(skin) { assert(skin > 0); }

void ContactPairs::Exclude(std::span<const IndexEdge> pairs) {
  std::vector<IndexEdge> sorted;
  sorted.reserve(pairs.size());
  int cells = 0;
  for (const IndexEdge& e : pairs) {
    assert(e.a >= 0 && e.b >= 0);
    if (e.a == e.b) continue;
    sorted.push_back({std::min(e.a, e.b), std::max(e.a, e.b)});
    cells = std::max(cells, sorted.back().b + 1);
  }
  std::sort(sorted.begin(), sorted.end());
  sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
  excluded_.clear();
  excluded_begin_.assign(sorted.empty() ? 0 : cells + 1, 0);
  for (const IndexEdge& e : sorted) {
    excluded_.push_back(e.b);
    ++excluded_begin_[e.a + 1];
  }
  for (size_t i = 1; i < excluded_begin_.size(); ++i) {
    excluded_begin_[i] += excluded_begin_[i - 1];
  }
  built_at_.clear();  // The next Update rebuilds the list.
  last_seen_.clear();
  row_begin_.clear();  // And its bounds.
}

void ContactPairs::Update(std::span<const Vec2> position,
                          std::span<const double> radius, double range) {
  assert(position.size() == radius.size());
  // The same bits as the last Update: the list is as valid (or as exact,
  // out of bounds) as it was then.
  if (builds_ > 0 && range == built_range_ &&
      position.size() == last_seen_.size() &&
      std::memcmp(position.data(), last_seen_.data(),
                  position.size() * sizeof(Vec2)) == 0) {
    return;
  }
  ++moves_;
  if (range != built_range_ || !Valid(position)) {
    Build(position, radius, range);
  }
  last_seen_.assign(position.begin(), position.end());
}

bool ContactPairs::Valid(std::span<const Vec2> position) const {
  if (builds_ == 0 || position.size() != built_at_.size()) return false;
  const double limit = kMoveFraction * skin_;
  kernels::WithinMoveArgs args;
  args.points = position.size();
  args.position = position.data();
  args.built = built_at_.data();
  // InBounds and the move, in vectors; NaN makes the list invalid.
  args.bound = kBound;
  args.limit2 = limit * limit;
  return kernels::WithinMove(ActiveIsa(), args);
}

void ContactPairs::MakeBounds(std::span<const double> radius, double range) {
  if (!row_begin_.empty() && range == bounds_range_ &&
      radius.size() == bounds_radius_.size() &&
      std::memcmp(radius.data(), bounds_radius_.data(),
                  radius.size() * sizeof(double)) == 0) {
    return;
  }
  const int n = static_cast<int>(radius.size());
  bounds_range_ = range;
  bounds_radius_.assign(radius.begin(), radius.end());
  row_begin_.assign(1, 0);
  bound2_.clear();
  const int excluding = static_cast<int>(excluded_begin_.size()) - 1;
  for (int i = 0; i < n; ++i) {
    // Cell i's excluded partners, increasing, walked alongside j.
    const int* skip = nullptr;
    const int* skip_end = nullptr;
    if (i < excluding) {
      skip = excluded_.data() + excluded_begin_[i];
      skip_end = excluded_.data() + excluded_begin_[i + 1];
    }
    for (int j = i + 1; j < n; ++j) {
      if (skip != skip_end && *skip == j) {
        ++skip;
        bound2_.push_back(-1.0);
        continue;
      }
      const double bound = Reach(range, radius[i] + radius[j]) + skin_;
      bound2_.push_back(bound * bound);
    }
    // Padded to whole vectors of the kernel with pairs never listed.
    while ((bound2_.size() - row_begin_.back()) % kRowPad != 0) {
      bound2_.push_back(-1.0);
    }
    row_begin_.push_back(static_cast<int>(bound2_.size()));
  }
}

void ContactPairs::Build(std::span<const Vec2> position,
                         std::span<const double> radius, double range) {
  const int n = static_cast<int>(position.size());
  ++builds_;
  built_range_ = range;
  built_at_.assign(position.begin(), position.end());
  MakeBounds(radius, range);
  bool in_bounds = true;
  x_.assign(static_cast<size_t>(n) + kRowPad, 0.0);
  y_.assign(static_cast<size_t>(n) + kRowPad, 0.0);
  for (int i = 0; i < n; ++i) {
    in_bounds &= InBounds(position[i]);
    x_[i] = position[i].x;
    y_[i] = position[i].y;
  }
  // A pair is left out only when farther than the mechanics' own
  // pre-filter would let through, even with the skin added; NaN stays in
  // (kernels::NearPairs).
  begin_.resize(static_cast<size_t>(n) + 1);
  partner_.resize(bound2_.size() + 8);  // Room for the kernel's stores.
  const Isa isa = ActiveIsa();
  kernels::NearPairsArgs row;
  row.x = x_.data();
  row.y = y_.data();
  int count = 0;
  begin_[0] = 0;
  for (int i = 0; i < n; ++i) {
    row.first = i + 1;
    row.last = i + 1 + (row_begin_[i + 1] - row_begin_[i]);
    row.xi = x_[i];
    row.yi = y_[i];
    row.bound2 = bound2_.data() + row_begin_[i];
    row.out = partner_.data() + count;
    count += kernels::NearPairs(isa, row);
    begin_[i + 1] = count;
  }
  // Out of bounds, the list is exact for these positions only: the next
  // Update() rebuilds it.
  if (!in_bounds) built_at_.clear();
}

}  // namespace animat
