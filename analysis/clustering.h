// Unsupervised grouping of feature vectors, and how well two groupings
// agree: standardisation with absent values, Ward's hierarchical
// clustering, the adjusted Rand index, and the first principal components
// (docs/analysis.md, "Clusters"). Pure functions; deterministic (the same
// bits for the same inputs and binary: ties are broken by index, Eigen's
// solver runs single-threaded); thread-safe.
#ifndef ANIMAT_ANALYSIS_CLUSTERING_H_
#define ANIMAT_ANALYSIS_CLUSTERING_H_

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace animat::analysis {

// Rows (one per item) of `names.size()` features each, some absent.
struct FeatureTable {
  std::vector<std::string> names;
  std::vector<std::vector<std::optional<double>>> rows;
};

struct Standardised {
  std::vector<std::string> names;  // The features kept, in table order.
  // The features left out: absent from every row, or the same in every
  // row that has them (no spread to standardise by).
  std::vector<std::string> dropped;
  // Per row, per kept feature: (x − mean) / standard deviation over the
  // rows that have it (population deviation); an absent value is 0, that
  // mean, so that it pulls the row towards no side.
  std::vector<std::vector<double>> rows;
  std::vector<int> absent;  // Per row, the kept features it lacks.
};

Standardised Standardise(const FeatureTable& table);

// One merge of Ward's agglomerative clustering.
struct WardMerge {
  int a = 0;  // The clusters merged, each named by its smallest item.
  int b = 0;  // a < b.
  // Ward's distance between them, √(2·n_a·n_b / (n_a + n_b))·‖c_a − c_b‖
  // (scipy's `ward` linkage height), c the clusters' centroids.
  double height = 0;
  int size = 0;  // Items in the merged cluster.
};

// The n − 1 merges of Ward's method on the Euclidean distances between
// `points` (all of one length), in order; heights never decrease. Ties:
// the pair with the smallest (a, b). Empty for fewer than 2 points.
std::vector<WardMerge> WardLinkage(
    const std::vector<std::vector<double>>& points);

// The clusters after the first n − k merges, for n items: each item's
// cluster, numbered 0, 1, ... in the order of their smallest items. k is
// clamped to [1, n].
std::vector<int> CutTree(const std::vector<WardMerge>& merges, int n, int k);

// The k in [2, max_k] (max_k clamped to n − 1) after whose last merge the
// next merge's height rises most (ties: the smaller k); n when n < 3.
int LargestGapClusters(const std::vector<WardMerge>& merges, int n, int max_k);

// The adjusted Rand index of two partitions of the same items (Hubert and
// Arabie, 1985): 1 for the same partition up to names, about 0 for
// unrelated ones, down to −0.5. 1 when the expected index is already the
// largest (both partitions one cluster, or both every item alone). The
// partitions must have the same length.
double AdjustedRandIndex(const std::vector<int>& a, const std::vector<int>& b);

// The rows projected on the first two principal components of their
// covariance (the rows are taken as centred, as Standardise makes them).
struct Projection {
  std::vector<std::array<double, 2>> points;
  // Share of the total variance each component holds, in [0, 1].
  std::array<double, 2> explained = {0, 0};
  // Each component's weights over the features (unit length), its
  // largest-magnitude weight positive (ties: the first).
  std::array<std::vector<double>, 2> loadings;
};

// Fewer than two features or rows leave the missing components 0.
Projection PrincipalComponents(const std::vector<std::vector<double>>& rows);

}  // namespace animat::analysis

#endif  // ANIMAT_ANALYSIS_CLUSTERING_H_
