#include "analysis/strategy_clusters.h"

#include <algorithm>
#include <cstdio>

namespace animat::analysis {
namespace {

FeatureTable TableOf(const std::vector<LabelledAnimat>& animats) {
  FeatureTable table;
  table.names = StrategyFeatureNames();
  for (const LabelledAnimat& a : animats) {
    std::vector<std::optional<double>> row;
    for (const std::string& name : table.names) {
      row.push_back(FeatureValue(a.strategy.features, name));
    }
    table.rows.push_back(std::move(row));
  }
  return table;
}

std::vector<int> LabelsOf(const std::vector<LabelledAnimat>& animats) {
  std::vector<int> labels;
  for (const LabelledAnimat& a : animats) {
    labels.push_back(static_cast<int>(a.strategy.label));
  }
  return labels;
}

}  // namespace

StrategyClustering ClusterStrategies(const std::vector<LabelledAnimat>& animats,
                                     std::optional<int> clusters) {
  StrategyClustering c;
  const int n = static_cast<int>(animats.size());
  const Standardised table = Standardise(TableOf(animats));
  c.features = table.names;
  c.dropped = table.dropped;
  c.merges = WardLinkage(table.rows);
  c.clusters_given = clusters.has_value();
  c.clusters = clusters ? std::clamp(*clusters, 1, std::max(n, 1))
                        : LargestGapClusters(c.merges, n, kMaxClusters);
  const std::vector<int> labels = LabelsOf(animats);
  const std::vector<int> cut = CutTree(c.merges, n, c.clusters);
  c.agreement = AdjustedRandIndex(cut, labels);
  for (int k = 2; k <= std::min(kMaxClusters, n - 1); ++k) {
    c.agreement_by_clusters.push_back(
        AdjustedRandIndex(CutTree(c.merges, n, k), labels));
  }
  c.projection = PrincipalComponents(table.rows);
  for (int i = 0; i < n; ++i) {
    const LabelledAnimat& a = animats[i];
    ClusteredAnimat out;
    out.name = a.name;
    out.label = a.strategy.label;
    out.margin = a.strategy.margin;
    out.stable = a.strategy.Sensitive().empty();
    out.fitness = a.fitness;
    out.cluster = cut[i];
    out.position = c.projection.points[i];
    out.absent = table.absent[i];
    out.features = a.strategy.features;
    c.animats.push_back(out);
  }
  return c;
}

v1::StrategyClustering StrategyClusteringToProto(const StrategyClustering& c) {
  v1::StrategyClustering out;
  for (const ClusteredAnimat& a : c.animats) {
    v1::ClusteredAnimat* p = out.add_animat();
    p->set_name(a.name);
    p->set_label(StrategyLabelToProto(a.label));
    p->set_margin(a.margin);
    p->set_stable(a.stable);
    if (a.fitness) p->set_fitness(*a.fitness);
    p->set_cluster(a.cluster);
    p->set_pc1(a.position[0]);
    p->set_pc2(a.position[1]);
    p->set_absent_features(a.absent);
    StrategyFeaturesToProto(a.features, p->mutable_features());
  }
  for (const std::string& f : c.features) out.add_feature(f);
  for (const std::string& f : c.dropped) out.add_dropped_feature(f);
  out.set_clusters(c.clusters);
  out.set_clusters_given(c.clusters_given);
  out.set_adjusted_rand_index(c.agreement);
  for (double ari : c.agreement_by_clusters) {
    out.add_adjusted_rand_index_by_clusters(ari);
  }
  for (const WardMerge& m : c.merges) {
    v1::ClusterMerge* p = out.add_merge();
    p->set_a(m.a);
    p->set_b(m.b);
    p->set_height(m.height);
    p->set_size(m.size);
  }
  out.set_explained_pc1(c.projection.explained[0]);
  out.set_explained_pc2(c.projection.explained[1]);
  for (double w : c.projection.loadings[0]) out.add_loading_pc1(w);
  for (double w : c.projection.loadings[1]) out.add_loading_pc2(w);
  return out;
}

std::string StrategyClusteringSummary(const StrategyClustering& c) {
  size_t width = 6;
  for (const ClusteredAnimat& a : c.animats) {
    width = std::max(width, a.name.size());
  }
  char line[512];
  std::snprintf(line, sizeof(line), "%-*s  %-9s  %6s  %-6s  %7s  %7s  %7s\n",
                static_cast<int>(width), "animat", "label", "margin", "stable",
                "cluster", "pc1", "pc2");
  std::string text = line;
  for (const ClusteredAnimat& a : c.animats) {
    std::snprintf(line, sizeof(line),
                  "%-*s  %-9s  %6.3f  %-6s  %7d  %+7.3f  %+7.3f\n",
                  static_cast<int>(width), a.name.c_str(),
                  StrategyName(a.label), a.margin, a.stable ? "yes" : "no",
                  a.cluster, a.position[0], a.position[1]);
    text += line;
  }
  std::snprintf(line, sizeof(line),
                "%d %s (%s) of %zu %s on %zu features; adjusted Rand index "
                "against the labels %.3f\n",
                c.clusters, c.clusters == 1 ? "cluster" : "clusters",
                c.clusters_given ? "as asked" : "the largest gap in heights",
                c.animats.size(), c.animats.size() == 1 ? "animat" : "animats",
                c.features.size(), c.agreement);
  text += line;
  text += "by clusters:";
  for (size_t i = 0; i < c.agreement_by_clusters.size(); ++i) {
    std::snprintf(line, sizeof(line), " %zu: %.3f", i + 2,
                  c.agreement_by_clusters[i]);
    text += line;
  }
  return text + "\n";
}

}  // namespace animat::analysis
