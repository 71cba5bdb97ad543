// Tests of the genome-to-network map (docs/model.md §2): affinities, parsing
// into nodes, who binds whom, summed multigraph weights and viability.
//
// Expected values are written from the model's words with std::exp and
// std::sqrt, never taken from the code under test. Genomes are built by
// hand; elements meant not to interact are placed at least 3 apart.
#include "common/grn/network.h"
#include "tests/genome_builder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <initializer_list>
#include <vector>

#include "common/genome/genome.h"
#include "common/grn/grn_params.h"

namespace animat {
namespace {

// Weights are at most 10; 1e-13 is ~50 ulp there, far below any model
// change (a different decay or sign) yet above exp's rounding.
constexpr double kWeightTolerance = 1e-13;

using testing::GInt;
using testing::GMor;
using testing::In;
using testing::MakeGenome;
using testing::Out;
using testing::P;

// Builds with the model defaults, checking the genome is valid first.
Network Build(const Genome& genome) {
  const Status status = ValidateGenome(genome);
  EXPECT_TRUE(status.ok()) << status.ToString();
  return Network::Build(genome, GrnParams{});
}

// model §2, written out independently: sign·sign·10·exp(−d) for d < 3.
double ModelAffinity(const Element& f, const Element& r) {
  const double dx = f.x - r.x;
  const double dy = f.y - r.y;
  const double d = std::sqrt(dx * dx + dy * dy);
  if (!(d < 3.0)) return 0.0;
  return f.sign * r.sign * 10.0 * std::exp(-d);
}

void ExpectNode(const Node& node, NodeKind kind, int first_element, int channel,
                const std::vector<int>& regions,
                const std::vector<int>& factors) {
  EXPECT_EQ(node.kind, kind);
  EXPECT_EQ(node.first_element, first_element);
  EXPECT_EQ(node.channel, channel);
  EXPECT_EQ(node.regions, regions);
  EXPECT_EQ(node.factors, factors);
}

void ExpectUnit(const Node& node, int first_element,
                const std::vector<int>& regions,
                const std::vector<int>& factors) {
  ExpectNode(node, NodeKind::kUnit, first_element, -1, regions, factors);
}

int Ch(InputChannel c) { return static_cast<int>(c); }
int Ch(OutputChannel c) { return static_cast<int>(c); }

// ---------------------------------------------------------------------------
// Affinity

TEST(GrnParamsTest, DefaultsAreModelConstants) {
  const GrnParams params;
  EXPECT_EQ(params.weight_max, 10.0);
  EXPECT_EQ(params.decay_length, 1.0);
  EXPECT_EQ(params.cutoff, 3.0);
  EXPECT_EQ(params.dt, 0.05);
}

TEST(AffinityTest, OverlappingPointsGiveTenTimesSignProduct) {
  const GrnParams params;
  for (int sf : {1, -1}) {
    for (int sr : {1, -1}) {
      SCOPED_TRACE(::testing::Message() << "signs " << sf << " " << sr);
      const Element f = GInt(3.25, 4.5, sf);
      const Element r = P(3.25, 4.5, sr);
      EXPECT_EQ(Affinity(f, r, params), 10.0 * sf * sr);
      EXPECT_TRUE(Binds(f, r, params));
    }
  }
}

TEST(AffinityTest, DecaysAsTenExpMinusDistanceForEverySignProduct) {
  const GrnParams params;
  for (double d : {1.0, 2.0, 2.999}) {
    for (int sf : {1, -1}) {
      for (int sr : {1, -1}) {
        SCOPED_TRACE(::testing::Message()
                     << "d " << d << " signs " << sf << " " << sr);
        const double expected = sf * sr * 10.0 * std::exp(-d);
        const Element r = P(0.0, 0.0, sr);
        // Along x, along y, and with the factor on the other side.
        for (const Element& f :
             {GInt(d, 0.0, sf), GMor(0.0, d, sf), GInt(-d, 0.0, sf)}) {
          EXPECT_NEAR(Affinity(f, r, params), expected, kWeightTolerance);
          EXPECT_TRUE(Binds(f, r, params));
        }
        // Either factor kind and an S_OUT region: the rule is the same.
        EXPECT_NEAR(Affinity(In(InputChannel::kUniform, 0.0, d, sf),
                             Out(OutputChannel::kSize, 0.0, 0.0, sr), params),
                    expected, kWeightTolerance);
      }
    }
  }
  // Spot values, so the formula above is not only checked against itself.
  EXPECT_NEAR(Affinity(GInt(1.0, 0.0), P(0.0, 0.0), params), 3.678794411714423,
              1e-14);
  EXPECT_NEAR(Affinity(GInt(0.0, 2.999), P(0.0, 0.0, -1), params),
              -0.49836880338065903, 1e-14);
}

TEST(AffinityTest, UsesEuclideanDistanceInThePlane) {
  const GrnParams params;
  // dx = 1.5, dy = -1.75 exactly: d = sqrt(5.3125).
  const Element f = GInt(6.5, 5.25, -1);
  const Element r = P(5.0, 7.0, 1);
  const double d = std::sqrt(1.5 * 1.5 + 1.75 * 1.75);
  EXPECT_NEAR(Affinity(f, r, params), -10.0 * std::exp(-d), kWeightTolerance);
  // Not the sum of |dx| + |dy| (3.25, which would not bind).
  EXPECT_TRUE(Binds(f, r, params));
}

TEST(AffinityTest, IsExactlyZeroAtDistanceThreeAndBeyond) {
  const GrnParams params;
  const Element r = P(2.0, 5.0);
  const double beyond_three = std::nextafter(3.0, 4.0);
  for (const Element& f :
       {GInt(5.0, 5.0), GInt(-1.0, 5.0, -1), GMor(2.0, 8.0), GInt(2.0, 2.0),
        GInt(2.0 + beyond_three, 5.0), GInt(5.5, 5.0), GInt(52.0, 55.0)}) {
    SCOPED_TRACE(::testing::Message() << "factor at " << f.x << ", " << f.y);
    EXPECT_EQ(Affinity(f, r, params), 0.0);
    EXPECT_FALSE(Binds(f, r, params));
  }
}

TEST(AffinityTest, JustBelowThreeBinds) {
  const GrnParams params;
  const double d = std::nextafter(3.0, 0.0);
  const Element f = GInt(d, 0.0);
  const Element r = P(0.0, 0.0, -1);
  EXPECT_TRUE(Binds(f, r, params));
  EXPECT_NEAR(Affinity(f, r, params), -10.0 * std::exp(-d), kWeightTolerance);
  EXPECT_LT(Affinity(f, r, params), -0.49);
}

// Two offsets where sqrt(dx*dx + dy*dy) in double and the exactly rounded
// distance (hypot) fall on opposite sides of the cut-off 3: model §2.2 fixes
// the first.
TEST(AffinityTest, DistanceIsSqrtOfSumOfSquaresNotHypot) {
  const GrnParams params;
  {
    const double x = 0x1.53b0eb69002adp+1, y = 0x1.6623b15e39441p+0;
    const double d = std::sqrt(x * x + y * y);
    ASSERT_LT(d, 3.0);  // The true distance rounds to 3.0.
    const Element f = GInt(x, y);
    const Element r = P(0.0, 0.0);
    EXPECT_TRUE(Binds(f, r, params));
    EXPECT_NEAR(Affinity(f, r, params), 10.0 * std::exp(-d), kWeightTolerance);
    EXPECT_GT(Affinity(f, r, params), 0.49);
  }
  {
    const double x = 0x1.f9d14ff15252dp+0, y = 0x1.20f3a7fb3783bp+1;
    ASSERT_EQ(std::sqrt(x * x + y * y), 3.0);  // The true distance is < 3.
    const Element f = GInt(0.0, 0.0);
    const Element r = P(x, y);
    EXPECT_FALSE(Binds(f, r, params));
    EXPECT_EQ(Affinity(f, r, params), 0.0);
  }
}

// ---------------------------------------------------------------------------
// Parsing into nodes

TEST(NetworkTest, PRunThenGRunIsOneUnit) {
  const Network net =
      Build(MakeGenome({P(0, 0), P(10, 0), GInt(20, 0), GInt(30, 0)}));
  ASSERT_EQ(net.node_count(), 1);
  ExpectUnit(net.nodes()[0], 0, {0, 1}, {2, 3});
  EXPECT_TRUE(net.nodes()[0].makes_internal);
  EXPECT_FALSE(net.nodes()[0].makes_morphogen);
  EXPECT_EQ(net.nodes()[0].morphogen, -1);
  EXPECT_EQ(net.morphogen_count(), 0);
}

TEST(NetworkTest, OrphanPBeforeSIsIgnored) {
  {
    const Network net =
        Build(MakeGenome({P(0, 0), In(InputChannel::kUniform, 50, 50)}));
    ASSERT_EQ(net.node_count(), 1);
    ExpectNode(net.nodes()[0], NodeKind::kInput, 1, Ch(InputChannel::kUniform),
               {}, {1});
  }
  {
    const Network net = Build(
        MakeGenome({P(0, 0), P(5, 0), Out(OutputChannel::kDivide, 50, 50)}));
    ASSERT_EQ(net.node_count(), 1);
    ExpectNode(net.nodes()[0], NodeKind::kOutput, 2, Ch(OutputChannel::kDivide),
               {2}, {});
  }
}

TEST(NetworkTest, OrphanPAtEndIsIgnored) {
  {
    const Network net = Build(MakeGenome({P(0, 0), GInt(10, 0), P(20, 0)}));
    ASSERT_EQ(net.node_count(), 1);
    ExpectUnit(net.nodes()[0], 0, {0}, {1});
  }
  {
    const Network net = Build(
        MakeGenome({In(InputChannel::kMaternal1, 50, 50), P(0, 0), P(10, 0)}));
    ASSERT_EQ(net.node_count(), 1);
    ExpectNode(net.nodes()[0], NodeKind::kInput, 0,
               Ch(InputChannel::kMaternal1), {}, {0});
  }
}

TEST(NetworkTest, OrphanGAtStartIsIgnored) {
  const Network net =
      Build(MakeGenome({GInt(0, 0), GMor(10, 0), P(20, 0), GInt(30, 0)}));
  ASSERT_EQ(net.node_count(), 1);
  ExpectUnit(net.nodes()[0], 2, {2}, {3});
  EXPECT_FALSE(net.nodes()[0].makes_morphogen);
  EXPECT_EQ(net.morphogen_count(), 0);
}

TEST(NetworkTest, OrphanGAfterSIsIgnored) {
  const Network net =
      Build(MakeGenome({P(0, 0), GInt(10, 0), Out(OutputChannel::kSize, 50, 50),
                        GMor(20, 0), GInt(30, 0), P(40, 0), GInt(60, 0),
                        In(InputChannel::kMaternal2, 70, 70), GMor(80, 0)}));
  ASSERT_EQ(net.node_count(), 4);
  ExpectUnit(net.nodes()[0], 0, {0}, {1});
  ExpectNode(net.nodes()[1], NodeKind::kOutput, 2, Ch(OutputChannel::kSize),
             {2}, {});
  ExpectUnit(net.nodes()[2], 5, {5}, {6});
  ExpectNode(net.nodes()[3], NodeKind::kInput, 7, Ch(InputChannel::kMaternal2),
             {}, {7});
  EXPECT_EQ(net.morphogen_count(), 0);
}

TEST(NetworkTest, SElementBreaksARunInProgress) {
  {
    const Network net = Build(MakeGenome(
        {P(0, 0), In(InputChannel::kMaternal0, 50, 50), GInt(9, 0)}));
    ASSERT_EQ(net.node_count(), 1);
    ExpectNode(net.nodes()[0], NodeKind::kInput, 1,
               Ch(InputChannel::kMaternal0), {}, {1});
  }
  {
    const Network net =
        Build(MakeGenome({P(0, 0), P(10, 0), Out(OutputChannel::kSize, 50, 50),
                          GMor(20, 0), GInt(30, 0)}));
    ASSERT_EQ(net.node_count(), 1);
    ExpectNode(net.nodes()[0], NodeKind::kOutput, 2, Ch(OutputChannel::kSize),
               {2}, {});
    EXPECT_EQ(net.morphogen_count(), 0);
  }
}

TEST(NetworkTest, SeveralSElementsOfOneChannelAreSeveralNodes) {
  const Network net = Build(MakeGenome(
      {Out(OutputChannel::kDivide, 0, 0), Out(OutputChannel::kDivide, 0, 0),
       In(InputChannel::kUniform, 20, 20), Out(OutputChannel::kDivide, 0, 0),
       In(InputChannel::kUniform, 20, 20)}));
  ASSERT_EQ(net.node_count(), 5);
  ExpectNode(net.nodes()[0], NodeKind::kOutput, 0, Ch(OutputChannel::kDivide),
             {0}, {});
  ExpectNode(net.nodes()[1], NodeKind::kOutput, 1, Ch(OutputChannel::kDivide),
             {1}, {});
  ExpectNode(net.nodes()[2], NodeKind::kInput, 2, Ch(InputChannel::kUniform),
             {}, {2});
  ExpectNode(net.nodes()[3], NodeKind::kOutput, 3, Ch(OutputChannel::kDivide),
             {3}, {});
  ExpectNode(net.nodes()[4], NodeKind::kInput, 4, Ch(InputChannel::kUniform),
             {}, {4});
  EXPECT_EQ(net.output_nodes(Ch(OutputChannel::kDivide)),
            (std::vector<int>{0, 1, 3}));
  EXPECT_EQ(net.input_nodes(Ch(InputChannel::kUniform)),
            (std::vector<int>{2, 4}));
  for (int c = 0; c < kInputChannels; ++c) {
    if (c != Ch(InputChannel::kUniform)) {
      EXPECT_TRUE(net.input_nodes(c).empty());
    }
  }
  for (int c = 0; c < kOutputChannels; ++c) {
    if (c != Ch(OutputChannel::kDivide)) {
      EXPECT_TRUE(net.output_nodes(c).empty());
    }
  }
}

TEST(NetworkTest, PGPGIsTwoUnits) {
  const Network net =
      Build(MakeGenome({P(0, 0), GInt(10, 0), P(20, 0), GMor(30, 0)}));
  ASSERT_EQ(net.node_count(), 2);
  ExpectUnit(net.nodes()[0], 0, {0}, {1});
  ExpectUnit(net.nodes()[1], 2, {2}, {3});
  EXPECT_TRUE(net.nodes()[0].makes_internal);
  EXPECT_FALSE(net.nodes()[0].makes_morphogen);
  EXPECT_FALSE(net.nodes()[1].makes_internal);
  EXPECT_TRUE(net.nodes()[1].makes_morphogen);
  EXPECT_EQ(net.nodes()[1].morphogen, 0);
}

TEST(NetworkTest, UnitMakingBothFactorKindsIsInternalAndMorphogen) {
  const Network net = Build(
      MakeGenome({P(0, 0), GMor(10, 0), Out(OutputChannel::kExpand, 50, 50),
                  P(20, 0), GInt(30, 0), GMor(40, 0), GInt(60, 0)}));
  ASSERT_EQ(net.node_count(), 3);
  ExpectUnit(net.nodes()[0], 0, {0}, {1});
  ExpectNode(net.nodes()[1], NodeKind::kOutput, 2, Ch(OutputChannel::kExpand),
             {2}, {});
  ExpectUnit(net.nodes()[2], 3, {3}, {4, 5, 6});
  const Node& both = net.nodes()[2];
  EXPECT_TRUE(both.makes_internal);
  EXPECT_TRUE(both.makes_morphogen);
  EXPECT_EQ(both.morphogen, 1);
  EXPECT_FALSE(net.nodes()[0].makes_internal);
  EXPECT_EQ(net.nodes()[0].morphogen, 0);
  EXPECT_EQ(net.nodes()[1].morphogen, -1);
  EXPECT_EQ(net.morphogen_nodes(), (std::vector<int>{0, 2}));
}

TEST(NetworkTest, EmptyGenomeHasNoNodesAndIsNotViable) {
  const Network net = Build(Genome{});
  EXPECT_EQ(net.node_count(), 0);
  EXPECT_EQ(net.morphogen_count(), 0);
  EXPECT_TRUE(net.sources().empty());
  EXPECT_TRUE(net.targets().empty());
  EXPECT_TRUE(net.successors().empty());
  for (int c = 0; c < kInputChannels; ++c)
    EXPECT_TRUE(net.input_nodes(c).empty());
  for (int c = 0; c < kOutputChannels; ++c) {
    EXPECT_TRUE(net.output_nodes(c).empty());
  }
  const Viability v = net.CheckViability();
  EXPECT_FALSE(v.viable);
  EXPECT_FALSE(v.reason.empty());
}

TEST(NetworkTest, GenomeOfOnlyGElementsHasNoNodes) {
  const Network net = Build(MakeGenome({GInt(0, 0), GMor(0, 0), GInt(0, 0)}));
  EXPECT_EQ(net.node_count(), 0);
  EXPECT_EQ(net.morphogen_count(), 0);
}

TEST(NetworkTest, NodesAreOrderedByGenomeIndexOfFirstElement) {
  const Network net = Build(
      MakeGenome({Out(OutputChannel::kContract, 0, 0), P(10, 0), GInt(20, 0),
                  In(InputChannel::kMaternal0, 30, 0), GInt(40, 0), P(50, 0),
                  P(60, 0), GMor(70, 0), GInt(80, 0),
                  Out(OutputChannel::kRotateLeft, 90, 0), P(100, 0)}));
  ASSERT_EQ(net.node_count(), 5);
  ExpectNode(net.nodes()[0], NodeKind::kOutput, 0, Ch(OutputChannel::kContract),
             {0}, {});
  ExpectUnit(net.nodes()[1], 1, {1}, {2});
  ExpectNode(net.nodes()[2], NodeKind::kInput, 3, Ch(InputChannel::kMaternal0),
             {}, {3});
  ExpectUnit(net.nodes()[3], 5, {5, 6}, {7, 8});
  ExpectNode(net.nodes()[4], NodeKind::kOutput, 9,
             Ch(OutputChannel::kRotateLeft), {9}, {});
  EXPECT_EQ(net.nodes()[3].morphogen, 0);
  EXPECT_EQ(net.morphogen_nodes(), (std::vector<int>{3}));
}

// ---------------------------------------------------------------------------
// Binding rules

TEST(NetworkTest, GFactorBindsPRegionOfAnotherUnit) {
  // Node 0: P far away, G at the origin. Node 1: P at distance 1.
  const Genome genome =
      MakeGenome({P(20, 20), GInt(0, 0, -1), P(1, 0), GInt(40, 40)});
  const Network net = Build(genome);
  ASSERT_EQ(net.node_count(), 2);
  EXPECT_NEAR(net.Weight(SourceKind::kLevel, 0, 1), -10.0 * std::exp(-1.0),
              kWeightTolerance);
  EXPECT_EQ(net.Weight(SourceKind::kLevel, 1, 0), 0.0);
  EXPECT_EQ(net.Weight(SourceKind::kLevel, 0, 0), 0.0);
  EXPECT_EQ(net.successors()[0], (std::vector<int>{1}));
  EXPECT_TRUE(net.successors()[1].empty());
}

TEST(NetworkTest, GFactorBindsSOutRegion) {
  const Genome genome = MakeGenome(
      {P(20, 20), GInt(0, 0), Out(OutputChannel::kExpand, 0, 2, -1), P(40, 40),
       GMor(60, 60), Out(OutputChannel::kDivide, 60, 60.5)});
  const Network net = Build(genome);
  ASSERT_EQ(net.node_count(), 4);
  EXPECT_NEAR(net.Weight(SourceKind::kLevel, 0, 1), -10.0 * std::exp(-2.0),
              kWeightTolerance);
  EXPECT_EQ(net.successors()[0], (std::vector<int>{1}));
  // A morphogen factor binds the same way, as a morphogen source.
  EXPECT_NEAR(net.Weight(SourceKind::kMorphogen, 2, 3), 10.0 * std::exp(-0.5),
              kWeightTolerance);
  EXPECT_EQ(net.Weight(SourceKind::kLevel, 2, 3), 0.0);
  EXPECT_EQ(net.successors()[2], (std::vector<int>{3}));
}

TEST(NetworkTest, GFactorBindsItsOwnUnitsRegion) {
  const Network net = Build(MakeGenome({P(0, 0, -1), GInt(0, 1.5, -1)}));
  ASSERT_EQ(net.node_count(), 1);
  EXPECT_NEAR(net.Weight(SourceKind::kLevel, 0, 0), 10.0 * std::exp(-1.5),
              kWeightTolerance);
  EXPECT_EQ(net.successors()[0], (std::vector<int>{0}));
}

TEST(NetworkTest, InputFactorBindsPButNotSOut) {
  // The input sits exactly on an S_OUT (d = 0) and 0.5 from a P.
  const Genome genome = MakeGenome(
      {In(InputChannel::kUniform, 0, 0), P(0.5, 0), GInt(30, 30),
       Out(OutputChannel::kDivide, 0, 0), Out(OutputChannel::kExpand, 0, 1)});
  const Network net = Build(genome);
  ASSERT_EQ(net.node_count(), 4);
  EXPECT_NEAR(net.Weight(SourceKind::kInput, 0, 1), 10.0 * std::exp(-0.5),
              kWeightTolerance);
  EXPECT_EQ(net.Weight(SourceKind::kInput, 0, 2), 0.0);
  EXPECT_EQ(net.Weight(SourceKind::kInput, 0, 3), 0.0);
  EXPECT_EQ(net.successors()[0], (std::vector<int>{1}));
  EXPECT_EQ(net.input_source_count(), 1);
}

TEST(NetworkTest, OutputNodeIsNeverASource) {
  // Everything at one point: the unit binds itself and both outputs, the
  // input binds the unit; the outputs bind nothing and nothing binds the
  // input (it has no region).
  const Genome genome = MakeGenome(
      {Out(OutputChannel::kDivide, 0, 0), P(0, 0), GInt(0, 0),
       Out(OutputChannel::kExpand, 0, 0), In(InputChannel::kUniform, 0, 0)});
  const Network net = Build(genome);
  // Nodes: 0 DIVIDE, 1 unit, 2 EXPAND, 3 input.
  ASSERT_EQ(net.node_count(), 4);
  EXPECT_TRUE(net.successors()[0].empty());
  EXPECT_TRUE(net.successors()[2].empty());
  EXPECT_EQ(net.successors()[1], (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(net.successors()[3], (std::vector<int>{1}));
  for (SourceKind kind :
       {SourceKind::kInput, SourceKind::kLevel, SourceKind::kMorphogen}) {
    for (int to = 0; to < net.node_count(); ++to) {
      EXPECT_EQ(net.Weight(kind, 0, to), 0.0);
      EXPECT_EQ(net.Weight(kind, 2, to), 0.0);
      EXPECT_EQ(net.Weight(kind, to, 3), 0.0);
    }
  }
  for (const Source& source : net.sources()) {
    EXPECT_NE(net.nodes()[source.node].kind, NodeKind::kOutput);
  }
  // The input node is not a target of the dynamics either.
  for (int t : net.targets()) EXPECT_NE(t, 3);
}

TEST(NetworkTest, WeightSumsEveryRegionFactorPair) {
  // Source unit (node 0): two G_INTERNAL. Target unit (node 1): two P.
  // Every one of the four pairs is within 3, with mixed signs.
  const Genome genome =
      MakeGenome({P(50, 50), GInt(0, 1, 1), GInt(0.5, -1.25, -1), P(0, 0, 1),
                  P(0.5, 0, -1), GInt(30, 30)});
  const std::vector<Element>& e = genome.elements;
  double expected = 0.0;
  for (int f : {1, 2}) {
    for (int r : {3, 4}) {
      const double w = ModelAffinity(e[f], e[r]);
      ASSERT_NE(w, 0.0) << "pair " << f << ", " << r << " must be in range";
      expected += w;
    }
  }
  const Network net = Build(genome);
  ASSERT_EQ(net.node_count(), 2);
  EXPECT_NEAR(net.Weight(SourceKind::kLevel, 0, 1), expected, kWeightTolerance);
  // Not any single pair, nor one region's sum.
  EXPECT_GT(std::fabs(expected - ModelAffinity(e[1], e[3]) -
                      ModelAffinity(e[2], e[3])),
            0.1);
  EXPECT_EQ(net.successors()[0], (std::vector<int>{1}));
}

TEST(NetworkTest, InputWeightSumsOverTheUnitsRegions) {
  const Genome genome =
      MakeGenome({In(InputChannel::kMaternal2, 0, 0, -1), P(1, 0), P(0, -2.5),
                  P(0, 2), GInt(40, 40)});
  const std::vector<Element>& e = genome.elements;
  const double expected = ModelAffinity(e[0], e[1]) +
                          ModelAffinity(e[0], e[2]) + ModelAffinity(e[0], e[3]);
  const Network net = Build(genome);
  ASSERT_EQ(net.node_count(), 2);
  EXPECT_NEAR(net.Weight(SourceKind::kInput, 0, 1), expected, kWeightTolerance);
}

TEST(NetworkTest, UnitMakingBothKindsSplitsWeightByFactorKind) {
  // Source unit (node 0): G_INTERNAL, G_MORPHOGEN, G_INTERNAL; target P
  // and an S_OUT, all within range.
  const Genome genome =
      MakeGenome({P(50, 50), GInt(0, 1), GMor(1, 0, -1), GInt(-0.5, 0.5, -1),
                  P(0, 0), GInt(40, 40), Out(OutputChannel::kSize, 0.25, 0.1)});
  const std::vector<Element>& e = genome.elements;
  const Network net = Build(genome);
  ASSERT_EQ(net.node_count(), 3);
  for (int target : {1, 2}) {
    const Element& r = e[net.nodes()[target].regions[0]];
    SCOPED_TRACE(::testing::Message() << "target " << target);
    EXPECT_NEAR(net.Weight(SourceKind::kLevel, 0, target),
                ModelAffinity(e[1], r) + ModelAffinity(e[3], r),
                kWeightTolerance);
    EXPECT_NEAR(net.Weight(SourceKind::kMorphogen, 0, target),
                ModelAffinity(e[2], r), kWeightTolerance);
  }
  EXPECT_EQ(net.successors()[0], (std::vector<int>{1, 2}));
}

// ---------------------------------------------------------------------------
// Viability

TEST(ViabilityTest, InputThroughUnitToDivideAndExpandIsViable) {
  const Network net =
      Build(MakeGenome({In(InputChannel::kUniform, 0, 0), P(1, 0), GInt(10, 10),
                        Out(OutputChannel::kDivide, 10, 11),
                        Out(OutputChannel::kExpand, 11, 10)}));
  const Viability v = net.CheckViability();
  EXPECT_TRUE(v.viable) << v.reason;
}

TEST(ViabilityTest, PathThroughSeveralUnitsCounts) {
  // In -> A -> B -> C -> {DIVIDE, CONTRACT}; no EXPAND node at all.
  const Genome chain = MakeGenome(
      {In(InputChannel::kMaternal0, 0, 0), P(1, 0), GInt(10, 0), P(10, 1),
       GMor(20, 0), P(20, 1), GInt(30, 0), Out(OutputChannel::kDivide, 30, 1),
       Out(OutputChannel::kContract, 31, 0)});
  const Network net = Build(chain);
  EXPECT_EQ(net.successors()[0], (std::vector<int>{1}));
  EXPECT_EQ(net.successors()[1], (std::vector<int>{2}));
  EXPECT_EQ(net.successors()[2], (std::vector<int>{3}));
  EXPECT_EQ(net.successors()[3], (std::vector<int>{4, 5}));
  const Viability v = net.CheckViability();
  EXPECT_TRUE(v.viable) << v.reason;

  // Breaking the middle link (B's region moved away) breaks viability.
  Genome broken = chain;
  broken.elements[3] = P(-20, -20);
  const Viability b = Build(broken).CheckViability();
  EXPECT_FALSE(b.viable);
  EXPECT_FALSE(b.reason.empty());
}

TEST(ViabilityTest, PathsMayStartAtDifferentInputs) {
  // M0 -> A -> DIVIDE and M1 -> B -> EXPAND; neither input reaches both.
  const Network net = Build(MakeGenome(
      {In(InputChannel::kMaternal0, 0, 0), P(1, 0), GInt(10, 0),
       Out(OutputChannel::kDivide, 10, 1), In(InputChannel::kMaternal1, 50, 0),
       P(51, 0), GInt(60, 0), Out(OutputChannel::kExpand, 60, 1)}));
  ASSERT_EQ(net.node_count(), 6);
  EXPECT_EQ(net.successors()[1], (std::vector<int>{2}));
  EXPECT_EQ(net.successors()[4], (std::vector<int>{5}));
  const Viability v = net.CheckViability();
  EXPECT_TRUE(v.viable) << v.reason;
}

TEST(ViabilityTest, EdgeWhoseOppositeSignPairsCancelStillCounts) {
  // Unit A (node 1) has two factors mirrored about both outputs' regions,
  // with opposite signs: each output gets +X - X = 0 exactly.
  const Genome genome =
      MakeGenome({In(InputChannel::kUniform, 0, 0), P(0.5, 0), GInt(20, 21, 1),
                  GInt(20, 19, -1), Out(OutputChannel::kDivide, 20, 20),
                  Out(OutputChannel::kExpand, 20, 20, -1)});
  const Network net = Build(genome);
  ASSERT_EQ(net.node_count(), 4);
  EXPECT_EQ(net.Weight(SourceKind::kLevel, 1, 2), 0.0);
  EXPECT_EQ(net.Weight(SourceKind::kLevel, 1, 3), 0.0);
  EXPECT_EQ(net.successors()[1], (std::vector<int>{2, 3}));
  const Viability v = net.CheckViability();
  EXPECT_TRUE(v.viable) << v.reason;
}

TEST(ViabilityTest, NegativeWeightEdgeCounts) {
  const Network net =
      Build(MakeGenome({In(InputChannel::kUniform, 0, 0, -1), P(1, 0),
                        GInt(10, 10, -1), Out(OutputChannel::kDivide, 10, 11),
                        Out(OutputChannel::kContract, 11, 10)}));
  ASSERT_LT(net.Weight(SourceKind::kInput, 0, 1), 0.0);
  ASSERT_LT(net.Weight(SourceKind::kLevel, 1, 2), 0.0);
  EXPECT_TRUE(net.CheckViability().viable);
}

TEST(ViabilityTest, MissingDivideNodeIsNonViable) {
  const Network net =
      Build(MakeGenome({In(InputChannel::kUniform, 0, 0), P(1, 0), GInt(10, 10),
                        Out(OutputChannel::kExpand, 10, 11),
                        Out(OutputChannel::kContract, 11, 10),
                        Out(OutputChannel::kSize, 10, 10)}));
  const Viability v = net.CheckViability();
  EXPECT_FALSE(v.viable);
  EXPECT_FALSE(v.reason.empty());
}

TEST(ViabilityTest, UnreachableDivideIsNonViable) {
  const Network net =
      Build(MakeGenome({In(InputChannel::kUniform, 0, 0), P(1, 0), GInt(10, 10),
                        Out(OutputChannel::kExpand, 10, 11),
                        Out(OutputChannel::kDivide, 40, 40)}));
  const Viability v = net.CheckViability();
  EXPECT_FALSE(v.viable);
  EXPECT_FALSE(v.reason.empty());
}

TEST(ViabilityTest, MissingExpandAndContractIsNonViable) {
  const Network net =
      Build(MakeGenome({In(InputChannel::kUniform, 0, 0), P(1, 0), GInt(10, 10),
                        Out(OutputChannel::kDivide, 10, 11),
                        Out(OutputChannel::kSize, 11, 10)}));
  const Viability v = net.CheckViability();
  EXPECT_FALSE(v.viable);
  EXPECT_FALSE(v.reason.empty());
}

TEST(ViabilityTest, UnreachableExpandAndContractIsNonViable) {
  const Network net = Build(MakeGenome(
      {In(InputChannel::kUniform, 0, 0), P(1, 0), GInt(10, 10),
       Out(OutputChannel::kDivide, 10, 11), Out(OutputChannel::kExpand, 40, 40),
       Out(OutputChannel::kContract, 60, 60)}));
  const Viability v = net.CheckViability();
  EXPECT_FALSE(v.viable);
  EXPECT_FALSE(v.reason.empty());
}

TEST(ViabilityTest, NoInputsIsNonViable) {
  // A self-exciting unit bound to both outputs, but no input reaches it.
  const Genome genome =
      MakeGenome({P(0, 0), GInt(0, 1), Out(OutputChannel::kDivide, 0, 1.5),
                  Out(OutputChannel::kExpand, 0.5, 1)});
  const Network net = Build(genome);
  EXPECT_EQ(net.successors()[0], (std::vector<int>{0, 1, 2}));
  const Viability v = net.CheckViability();
  EXPECT_FALSE(v.viable);
  EXPECT_FALSE(v.reason.empty());

  // The same network with an input on the unit's region is viable.
  Genome with_input = genome;
  with_input.elements.push_back(In(InputChannel::kUniform, -1, 0));
  EXPECT_TRUE(Build(with_input).CheckViability().viable);
}

TEST(ViabilityTest, EdgesAreDirected) {
  // In -> A and B -> A, B -> {DIVIDE, EXPAND}: no path from In to B.
  const Network net = Build(
      MakeGenome({In(InputChannel::kUniform, 0, 0), P(1, 0), GInt(40, 40),
                  P(20, 20), GInt(1, 1), Out(OutputChannel::kDivide, 1, 2),
                  Out(OutputChannel::kExpand, 2, 1)}));
  ASSERT_EQ(net.node_count(), 5);
  EXPECT_EQ(net.successors()[2], (std::vector<int>{1, 3, 4}));
  EXPECT_FALSE(net.CheckViability().viable);
}

TEST(ViabilityTest, OutputNodeDoesNotRelayAPath) {
  // In -> A -> EXPAND; the EXPAND element is 2.5 from B's region and B
  // binds DIVIDE, but an output factor binds nothing.
  const Network net =
      Build(MakeGenome({In(InputChannel::kUniform, 0, 0), P(1, 0), GInt(10, 0),
                        Out(OutputChannel::kExpand, 10, 1), P(10, 3.5),
                        GInt(20, 20), Out(OutputChannel::kDivide, 20, 21)}));
  ASSERT_EQ(net.node_count(), 5);
  EXPECT_EQ(net.successors()[1], (std::vector<int>{2}));
  EXPECT_TRUE(net.successors()[2].empty());
  EXPECT_FALSE(net.CheckViability().viable);
}

TEST(ViabilityTest, InputDoesNotReachOutputsDirectly) {
  // The input sits on both outputs' regions; S_IN binds P only.
  const Network net = Build(MakeGenome({In(InputChannel::kUniform, 0, 0),
                                        Out(OutputChannel::kDivide, 0, 0),
                                        Out(OutputChannel::kExpand, 0, 0.5)}));
  EXPECT_TRUE(net.successors()[0].empty());
  EXPECT_FALSE(net.CheckViability().viable);
}

}  // namespace
}  // namespace animat
