#include "analysis/clustering.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace animat::analysis {
namespace {

TEST(AdjustedRandIndexTest, IsOneForTheSamePartitionUnderAnyNames) {
  EXPECT_EQ(AdjustedRandIndex({0, 0, 1, 1, 2}, {0, 0, 1, 1, 2}), 1);
  EXPECT_EQ(AdjustedRandIndex({0, 0, 1, 1, 2}, {2, 2, 0, 0, 1}), 1);
}

TEST(AdjustedRandIndexTest, MatchesThePublishedExamples) {
  // scikit-learn's documented values for adjusted_rand_score (after
  // Hubert and Arabie, 1985), worked by hand in the comments.
  // Pairs together: 1 of 2 in the first, 1 in the second, of 6:
  // (1 − 2/6) / (1.5 − 2/6) = 4/7.
  EXPECT_NEAR(AdjustedRandIndex({0, 0, 1, 1}, {0, 0, 1, 2}), 4.0 / 7, 1e-15);
  EXPECT_NEAR(AdjustedRandIndex({0, 0, 1, 2}, {0, 0, 1, 1}), 4.0 / 7, 1e-15);
  // (2 − 6·3/15) / (4.5 − 6·3/15) = 0.8 / 3.3.
  EXPECT_NEAR(AdjustedRandIndex({0, 0, 0, 1, 1, 1}, {0, 0, 1, 1, 2, 2}),
              0.8 / 3.3, 1e-15);
  // Perfectly discordant: (0 − 4/6) / (2 − 4/6).
  EXPECT_NEAR(AdjustedRandIndex({0, 0, 1, 1}, {0, 1, 0, 1}), -0.5, 1e-15);
  // One cluster against every item alone: nothing beyond chance.
  EXPECT_EQ(AdjustedRandIndex({0, 0, 0, 0}, {0, 1, 2, 3}), 0);
}

TEST(AdjustedRandIndexTest, IsSymmetric) {
  const std::vector<int> a = {0, 1, 1, 2, 2, 2, 0, 1};
  const std::vector<int> b = {1, 1, 0, 0, 2, 2, 2, 1};
  EXPECT_EQ(AdjustedRandIndex(a, b), AdjustedRandIndex(b, a));
}

TEST(WardLinkageTest, MatchesWardsHeightsOnALine) {
  // 0, 1, 5, 6, 20: the pairs at distance 1, then the pairs' centroids 5
  // apart (√(2·2·2/4)·5), then 17 from the last (√(2·4·1/5)·17).
  const std::vector<WardMerge> merges =
      WardLinkage({{0.0}, {1.0}, {5.0}, {6.0}, {20.0}});
  ASSERT_EQ(merges.size(), 4u);
  EXPECT_EQ(merges[0].a, 0);
  EXPECT_EQ(merges[0].b, 1);
  EXPECT_EQ(merges[0].height, 1);
  EXPECT_EQ(merges[1].a, 2);
  EXPECT_EQ(merges[1].b, 3);
  EXPECT_EQ(merges[1].height, 1);
  EXPECT_EQ(merges[2].a, 0);
  EXPECT_EQ(merges[2].b, 2);
  EXPECT_NEAR(merges[2].height, 5 * std::sqrt(2.0), 1e-12);
  EXPECT_EQ(merges[2].size, 4);
  EXPECT_EQ(merges[3].b, 4);
  EXPECT_NEAR(merges[3].height, 17 * std::sqrt(1.6), 1e-12);
  EXPECT_EQ(merges[3].size, 5);
}

TEST(WardLinkageTest, CutsAndTheLargestGap) {
  const std::vector<WardMerge> merges =
      WardLinkage({{0.0}, {1.0}, {5.0}, {6.0}, {20.0}});
  EXPECT_EQ(CutTree(merges, 5, 2), (std::vector<int>{0, 0, 0, 0, 1}));
  EXPECT_EQ(CutTree(merges, 5, 3), (std::vector<int>{0, 0, 1, 1, 2}));
  EXPECT_EQ(CutTree(merges, 5, 1), (std::vector<int>{0, 0, 0, 0, 0}));
  EXPECT_EQ(CutTree(merges, 5, 9), (std::vector<int>{0, 1, 2, 3, 4}));
  // Heights 1, 1, 7.1, 21.5: the largest rise is into 2 clusters.
  EXPECT_EQ(LargestGapClusters(merges, 5, 8), 2);
  // Three tight groups far apart.
  const std::vector<WardMerge> three =
      WardLinkage({{0.0}, {100.0}, {0.5}, {200.0}, {100.5}, {200.5}});
  EXPECT_EQ(LargestGapClusters(three, 6, 8), 3);
  EXPECT_EQ(CutTree(three, 6, 3), (std::vector<int>{0, 1, 0, 2, 1, 2}));
}

TEST(WardLinkageTest, FewPointsMergeTrivially) {
  EXPECT_TRUE(WardLinkage({}).empty());
  EXPECT_TRUE(WardLinkage({{1.0, 2.0}}).empty());
  EXPECT_EQ(LargestGapClusters({}, 1, 8), 1);
  EXPECT_EQ(CutTree({}, 1, 2), (std::vector<int>{0}));
}

TEST(StandardiseTest, ScalesEachFeatureAndPlacesAbsentValuesAtTheMean) {
  FeatureTable t;
  t.names = {"a", "b", "constant", "nowhere"};
  t.rows = {{1.0, 10.0, 5.0, std::nullopt},
            {3.0, std::nullopt, 5.0, std::nullopt},
            {5.0, 20.0, std::nullopt, std::nullopt}};
  const Standardised s = Standardise(t);
  EXPECT_EQ(s.names, (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(s.dropped, (std::vector<std::string>{"constant", "nowhere"}));
  ASSERT_EQ(s.rows.size(), 3u);
  // a: mean 3, deviation √(8/3).
  const double d = std::sqrt(8.0 / 3);
  EXPECT_NEAR(s.rows[0][0], -2 / d, 1e-15);
  EXPECT_NEAR(s.rows[1][0], 0, 1e-15);
  EXPECT_NEAR(s.rows[2][0], 2 / d, 1e-15);
  // b: mean 15 and deviation 5 over the two rows that have it.
  EXPECT_EQ(s.rows[0][1], -1);
  EXPECT_EQ(s.rows[1][1], 0);
  EXPECT_EQ(s.rows[2][1], 1);
  EXPECT_EQ(s.absent, (std::vector<int>{0, 1, 0}));
}

TEST(PrincipalComponentsTest, PointsOnALineHaveOneComponent) {
  const Projection p =
      PrincipalComponents({{-2, -4}, {-1, -2}, {1, 2}, {2, 4}});
  EXPECT_NEAR(p.explained[0], 1, 1e-12);
  EXPECT_NEAR(p.explained[1], 0, 1e-12);
  // Along (1, 2)/√5, its larger weight positive.
  EXPECT_NEAR(p.loadings[0][0], 1 / std::sqrt(5.0), 1e-12);
  EXPECT_NEAR(p.loadings[0][1], 2 / std::sqrt(5.0), 1e-12);
  EXPECT_NEAR(p.points[0][0], -2 * std::sqrt(5.0), 1e-12);
  EXPECT_NEAR(p.points[3][0], 2 * std::sqrt(5.0), 1e-12);
  for (const auto& point : p.points) EXPECT_NEAR(point[1], 0, 1e-12);
}

TEST(PrincipalComponentsTest, TheWiderSpreadComesFirst) {
  const Projection p = PrincipalComponents({{0, 3}, {0, -3}, {1, 0}, {-1, 0}});
  EXPECT_NEAR(p.explained[0], 18.0 / 20, 1e-12);
  EXPECT_NEAR(p.explained[1], 2.0 / 20, 1e-12);
  EXPECT_NEAR(std::abs(p.loadings[0][1]), 1, 1e-12);
  EXPECT_NEAR(p.points[0][0], 3, 1e-12);
}

}  // namespace
}  // namespace animat::analysis
