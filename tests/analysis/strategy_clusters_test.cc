#include "analysis/strategy_clusters.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

namespace animat::analysis {
namespace {

// Turtles and jellyfish, each kind apart from the other on four features
// and spread within by `d` on one: rise_fraction for both, end_taper (which
// turtles lack) for the jellyfish.
LabelledAnimat Turtle(double d) {
  StrategyFeatures f;
  f.lr_symmetry = 0.95;
  f.fb_symmetry = 0.4;
  f.irregularity = 0.01;
  f.synchrony = 0.2;
  f.rise_fraction = 0.5 + d;
  return {"turtle " + std::to_string(d), ClassifyStrategy(f), 10 + d};
}

LabelledAnimat Jellyfish(double d) {
  StrategyFeatures f;
  f.lr_symmetry = 0.97;
  f.fb_symmetry = 0.97;
  f.irregularity = 0.01;
  f.synchrony = 0.95;
  f.rise_fraction = 0.7 + d;
  f.end_taper = -0.5 + d;
  f.stroke_agreement = 0.4;
  return {"jellyfish " + std::to_string(d), ClassifyStrategy(f), 20 + d};
}

TEST(StrategyClustersTest,
     TwoWellSeparatedKindsAreTwoClustersAgreeingWithTheLabels) {
  const std::vector<LabelledAnimat> animats = {Turtle(0),    Jellyfish(0),
                                               Turtle(0.01), Jellyfish(0.01),
                                               Turtle(0.02), Jellyfish(0.02)};
  for (size_t i = 0; i < animats.size(); ++i) {
    ASSERT_EQ(animats[i].strategy.label,
              i % 2 == 0 ? StrategyLabel::kTurtle : StrategyLabel::kJellyfish)
        << StrategySummary(animats[i].strategy);
  }
  const StrategyClustering c = ClusterStrategies(animats, std::nullopt);
  EXPECT_EQ(c.clusters, 2);
  EXPECT_FALSE(c.clusters_given);
  EXPECT_EQ(c.agreement, 1);
  ASSERT_EQ(c.animats.size(), 6u);
  for (size_t i = 0; i < c.animats.size(); ++i) {
    EXPECT_EQ(c.animats[i].cluster, static_cast<int>(i % 2));
    EXPECT_EQ(c.animats[i].name, animats[i].name);
    EXPECT_EQ(c.animats[i].fitness, animats[i].fitness);
  }
  // Turtles lack end_taper, standing at the jellyfish's mean; the features
  // the same wherever present are left out.
  EXPECT_EQ(c.animats[0].absent, 1);
  EXPECT_EQ(c.animats[1].absent, 0);
  EXPECT_EQ(c.features,
            (std::vector<std::string>{"lr_symmetry", "fb_symmetry", "synchrony",
                                      "rise_fraction", "end_taper"}));
  // The kinds lie apart on the first component.
  EXPECT_LT(c.animats[0].position[0] * c.animats[1].position[0], 0);
  EXPECT_GT(c.projection.explained[0], 0.8);
  // Cuts into 2 ... 5 clusters.
  ASSERT_EQ(c.agreement_by_clusters.size(), 4u);
  EXPECT_EQ(c.agreement_by_clusters[0], 1);
  EXPECT_LT(c.agreement_by_clusters[1], 1);
}

TEST(StrategyClustersTest, LabelsThatMissTheGroupsAgreeByChanceOnly) {
  // Two groups of features, all labelled other: no agreement beyond
  // chance.
  std::vector<LabelledAnimat> animats;
  for (double d : {0.0, 0.01, 0.02}) {
    for (double base : {0.1, 0.9}) {
      StrategyFeatures f;
      f.synchrony = base + d;
      f.elongation = base - d;
      animats.push_back({"x", ClassifyStrategy(f), std::nullopt});
      ASSERT_EQ(animats.back().strategy.label, StrategyLabel::kOther);
    }
  }
  const StrategyClustering c = ClusterStrategies(animats, 2);
  EXPECT_TRUE(c.clusters_given);
  EXPECT_EQ(c.agreement, 0);
  EXPECT_EQ(c.features, (std::vector<std::string>{"synchrony", "elongation"}));
  EXPECT_EQ(c.dropped.size(), StrategyFeatureNames().size() - 2);
}

TEST(StrategyClustersTest, TheProtoAndTheSummaryCarryEveryAnimat) {
  const StrategyClustering c = ClusterStrategies(
      {Turtle(0), Jellyfish(0), Turtle(0.01), Jellyfish(0.01)}, std::nullopt);
  const v1::StrategyClustering p = StrategyClusteringToProto(c);
  ASSERT_EQ(p.animat_size(), 4);
  EXPECT_EQ(p.animat(0).label(), v1::StrategyAnalysis::TURTLE);
  EXPECT_EQ(p.animat(1).label(), v1::StrategyAnalysis::JELLYFISH);
  EXPECT_EQ(p.animat(1).features().end_taper(), -0.5);
  EXPECT_EQ(p.animat(2).cluster(), c.animats[2].cluster);
  EXPECT_EQ(p.animat(3).pc1(), c.animats[3].position[0]);
  EXPECT_EQ(p.clusters(), c.clusters);
  EXPECT_EQ(p.adjusted_rand_index(), c.agreement);
  EXPECT_EQ(p.merge_size(), 3);
  EXPECT_EQ(p.feature_size(), static_cast<int>(c.features.size()));
  EXPECT_EQ(p.loading_pc1_size(), static_cast<int>(c.features.size()));
  const std::string text = StrategyClusteringSummary(c);
  // A header, a row per animat, the agreement and the cuts.
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 7) << text;
  EXPECT_NE(text.find("jellyfish 0.010000  jellyfish"), std::string::npos)
      << text;
  EXPECT_NE(text.find("adjusted Rand index against the labels 1.000"),
            std::string::npos)
      << text;
}

TEST(StrategyClustersTest, OneAnimatIsItsOwnCluster) {
  const StrategyClustering c = ClusterStrategies({Turtle(0)}, std::nullopt);
  ASSERT_EQ(c.animats.size(), 1u);
  EXPECT_EQ(c.clusters, 1);
  EXPECT_EQ(c.animats[0].cluster, 0);
  EXPECT_EQ(c.agreement, 1);
  EXPECT_TRUE(c.agreement_by_clusters.empty());
}

}  // namespace
}  // namespace animat::analysis
