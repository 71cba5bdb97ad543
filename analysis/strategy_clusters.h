// Do the strategy labels find the groups the features make on their own?
// The feature vectors of a set of analysed animats are standardised,
// clustered by Ward's method without their labels, projected on their
// first two principal components, and the clusters compared with the
// labels by the adjusted Rand index (docs/analysis.md, "Clusters"). Pure
// function; deterministic; thread-safe.
#ifndef ANIMAT_ANALYSIS_STRATEGY_CLUSTERS_H_
#define ANIMAT_ANALYSIS_STRATEGY_CLUSTERS_H_

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "analysis/clustering.h"
#include "analysis/strategy.h"
#include "animat/v1/analysis.pb.h"

namespace animat::analysis {

// One analysed animat.
struct LabelledAnimat {
  std::string name;  // For people: a file name, "store.db #id".
  Strategy strategy;
  std::optional<double> fitness;
};

// Cluster counts whose agreement is listed, from 2 up to this.
inline constexpr int kMaxClusters = 8;

struct ClusteredAnimat {
  std::string name;
  StrategyLabel label = StrategyLabel::kOther;
  double margin = 0;
  bool stable = false;  // No threshold move changes the label.
  std::optional<double> fitness;
  int cluster = 0;
  std::array<double, 2> position = {0, 0};  // On the two components.
  int absent = 0;             // Features it lacks, standing at their mean.
  StrategyFeatures features;  // As measured.
};

struct StrategyClustering {
  std::vector<ClusteredAnimat> animats;  // In the order given.
  std::vector<std::string> features;     // Standardised and clustered on.
  std::vector<std::string> dropped;      // Absent or constant everywhere.
  int clusters = 0;                      // The cut used.
  bool clusters_given = false;           // Asked for, not the largest gap.
  double agreement = 0;  // Adjusted Rand index, clusters vs labels.
  // The agreement of every cut into k = 2 ... min(kMaxClusters, n − 1)
  // clusters, in order of k.
  std::vector<double> agreement_by_clusters;
  std::vector<WardMerge> merges;
  Projection projection;
};

// `clusters`: the cut; default the largest gap in Ward's heights among 2 ...
// kMaxClusters. Fewer than 2 animats: every animat its own cluster and
// an agreement of 1.
StrategyClustering ClusterStrategies(const std::vector<LabelledAnimat>& animats,
                                     std::optional<int> clusters);

v1::StrategyClustering StrategyClusteringToProto(const StrategyClustering& c);

// A table for people: one row per animat (name, label, margin, stable,
// cluster, position), then the agreement.
std::string StrategyClusteringSummary(const StrategyClustering& c);

}  // namespace animat::analysis

#endif  // ANIMAT_ANALYSIS_STRATEGY_CLUSTERS_H_
