#include "analysis/clustering.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numeric>

namespace animat::analysis {
namespace {

// Mean and population standard deviation of column `c` over the rows that
// have it; nullopt without a spread.
std::optional<std::pair<double, double>> ColumnScale(const FeatureTable& t,
                                                     size_t c) {
  double sum = 0;
  int count = 0;
  for (const auto& row : t.rows) {
    if (row[c]) {
      sum += *row[c];
      ++count;
    }
  }
  if (count == 0) return std::nullopt;
  // The same value wherever present: no spread (rounding aside).
  bool spread = false;
  const std::optional<double>* first = nullptr;
  for (const auto& row : t.rows) {
    if (!row[c]) continue;
    if (first == nullptr) first = &row[c];
    spread = spread || *row[c] != **first;
  }
  if (!spread) return std::nullopt;
  const double mean = sum / count;
  double square = 0;
  for (const auto& row : t.rows) {
    if (row[c]) square += (*row[c] - mean) * (*row[c] - mean);
  }
  const double deviation = std::sqrt(square / count);
  if (!(deviation > 0)) return std::nullopt;
  return std::make_pair(mean, deviation);
}

// n·(n − 1)/2.
double Pairs(double n) { return n * (n - 1) / 2; }

// Sets the sign of `v` so that its largest-magnitude entry is positive.
void FixSign(Eigen::VectorXd* v) {
  Eigen::Index largest = 0;
  for (Eigen::Index i = 1; i < v->size(); ++i) {
    if (std::abs((*v)(i)) > std::abs((*v)(largest))) largest = i;
  }
  if (v->size() > 0 && (*v)(largest) < 0) *v = -*v;
}

}  // namespace

Standardised Standardise(const FeatureTable& table) {
  Standardised out;
  out.rows.assign(table.rows.size(), {});
  out.absent.assign(table.rows.size(), 0);
  for (size_t c = 0; c < table.names.size(); ++c) {
    const std::optional<std::pair<double, double>> scale =
        ColumnScale(table, c);
    if (!scale) {
      out.dropped.push_back(table.names[c]);
      continue;
    }
    out.names.push_back(table.names[c]);
    for (size_t r = 0; r < table.rows.size(); ++r) {
      const std::optional<double>& x = table.rows[r][c];
      out.rows[r].push_back(x ? (*x - scale->first) / scale->second : 0.0);
      if (!x) ++out.absent[r];
    }
  }
  return out;
}

std::vector<WardMerge> WardLinkage(
    const std::vector<std::vector<double>>& points) {
  const int n = static_cast<int>(points.size());
  std::vector<WardMerge> merges;
  if (n < 2) return merges;
  // Squared Ward distances between the active clusters, Lance–Williams.
  std::vector<std::vector<double>> d(n, std::vector<double>(n, 0.0));
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      double square = 0;
      for (size_t f = 0; f < points[i].size(); ++f) {
        const double delta = points[i][f] - points[j][f];
        square += delta * delta;
      }
      d[i][j] = square;
    }
  }
  std::vector<int> size(n, 1);
  std::vector<bool> active(n, true);
  for (int step = 0; step + 1 < n; ++step) {
    int a = -1;
    int b = -1;
    for (int i = 0; i < n; ++i) {
      for (int j = i + 1; j < n; ++j) {
        if (!active[i] || !active[j]) continue;
        if (a < 0 || d[i][j] < d[a][b]) {
          a = i;
          b = j;
        }
      }
    }
    const double na = size[a];
    const double nb = size[b];
    for (int k = 0; k < n; ++k) {
      if (!active[k] || k == a || k == b) continue;
      const double nk = size[k];
      const double merged =
          ((na + nk) * d[k][a] + (nb + nk) * d[k][b] - nk * d[a][b]) /
          (na + nb + nk);
      d[k][a] = d[a][k] = merged;
    }
    merges.push_back({a, b, std::sqrt(d[a][b]), size[a] + size[b]});
    size[a] += size[b];
    active[b] = false;
  }
  return merges;
}

std::vector<int> CutTree(const std::vector<WardMerge>& merges, int n, int k) {
  k = std::clamp(k, 1, std::max(n, 1));
  std::vector<int> root(n);
  std::iota(root.begin(), root.end(), 0);
  // A cluster is named by its smallest item, which is its root here.
  for (int m = 0; m < n - k && m < static_cast<int>(merges.size()); ++m) {
    for (int& r : root) {
      if (r == merges[m].b) r = merges[m].a;
    }
  }
  std::vector<int> number(n, -1);
  std::vector<int> cluster(n);
  int next = 0;
  for (int i = 0; i < n; ++i) {
    if (number[root[i]] < 0) number[root[i]] = next++;
    cluster[i] = number[root[i]];
  }
  return cluster;
}

int LargestGapClusters(const std::vector<WardMerge>& merges, int n, int max_k) {
  if (n < 3) return n;
  max_k = std::clamp(max_k, 2, n - 1);
  int best = 2;
  double best_gap = -1;
  for (int k = 2; k <= max_k; ++k) {
    // n − k merges made; the next one is merges[n − k].
    const double gap = merges[n - k].height - merges[n - k - 1].height;
    if (gap > best_gap) {
      best = k;
      best_gap = gap;
    }
  }
  return best;
}

double AdjustedRandIndex(const std::vector<int>& a, const std::vector<int>& b) {
  const int n = static_cast<int>(a.size());
  const int ka = a.empty() ? 0 : *std::max_element(a.begin(), a.end()) + 1;
  const int kb = b.empty() ? 0 : *std::max_element(b.begin(), b.end()) + 1;
  std::vector<std::vector<int>> table(ka, std::vector<int>(kb, 0));
  std::vector<int> rows(ka, 0);
  std::vector<int> columns(kb, 0);
  for (int i = 0; i < n; ++i) {
    ++table[a[i]][b[i]];
    ++rows[a[i]];
    ++columns[b[i]];
  }
  double index = 0;
  for (const auto& row : table) {
    for (int count : row) index += Pairs(count);
  }
  double sum_a = 0;
  double sum_b = 0;
  for (int count : rows) sum_a += Pairs(count);
  for (int count : columns) sum_b += Pairs(count);
  const double expected = n < 2 ? 0 : sum_a * sum_b / Pairs(n);
  const double largest = (sum_a + sum_b) / 2;
  if (largest == expected) return 1;
  return (index - expected) / (largest - expected);
}

Projection PrincipalComponents(const std::vector<std::vector<double>>& rows) {
  Projection p;
  p.points.assign(rows.size(), {0, 0});
  const Eigen::Index n = static_cast<Eigen::Index>(rows.size());
  const Eigen::Index features =
      rows.empty() ? 0 : static_cast<Eigen::Index>(rows[0].size());
  if (n < 2 || features < 1) return p;
  Eigen::MatrixXd x(n, features);
  for (Eigen::Index r = 0; r < n; ++r) {
    for (Eigen::Index c = 0; c < features; ++c) x(r, c) = rows[r][c];
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(x.transpose() *
                                                              x);
  const Eigen::VectorXd& values = solver.eigenvalues();  // Ascending.
  const double total = values.cwiseMax(0.0).sum();
  for (int c = 0; c < 2 && c < features; ++c) {
    const Eigen::Index column = features - 1 - c;
    Eigen::VectorXd v = solver.eigenvectors().col(column);
    FixSign(&v);
    p.explained[c] = total > 0 ? std::max(0.0, values(column)) / total : 0.0;
    p.loadings[c].assign(v.data(), v.data() + v.size());
    const Eigen::VectorXd scores = x * v;
    for (Eigen::Index r = 0; r < n; ++r) p.points[r][c] = scores(r);
  }
  return p;
}

}  // namespace animat::analysis
