#include "common/genome/random_genome.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <initializer_list>
#include <vector>

#include <gtest/gtest.h>

#include "common/base/rng.h"
#include "common/genome/genome.h"

namespace animat {
namespace {

Genome Random(uint64_t seed, uint64_t individual, int units = 10) {
  RandomStream stream(seed, individual, StreamPurpose::kRandomGenome);
  return RandomGenome(stream, units);
}

int Count(const Genome& genome, ElementType type) {
  int n = 0;
  for (const Element& e : genome.elements) n += e.type == type;
  return n;
}

// Checks the structure of docs/model.md §9.3: `units` P elements, each
// immediately followed by one G element, and one S element per channel.
::testing::AssertionResult HasInitialStructure(const Genome& genome,
                                               int units) {
  const int s_elements = kPaperInputChannels + kOutputChannels;
  if (genome.elements.size() != static_cast<size_t>(2 * units + s_elements)) {
    return ::testing::AssertionFailure()
           << genome.elements.size() << " elements, want "
           << 2 * units + s_elements;
  }
  std::array<int, kPaperInputChannels> inputs{};
  std::array<int, kOutputChannels> outputs{};
  int p = 0;
  int g = 0;
  for (size_t i = 0; i < genome.elements.size(); ++i) {
    const Element& e = genome.elements[i];
    switch (e.type) {
      case ElementType::kP:
        ++p;
        if (i + 1 >= genome.elements.size() || !genome.elements[i + 1].IsG()) {
          return ::testing::AssertionFailure()
                 << "P at " << i << " is not followed by a G";
        }
        break;
      case ElementType::kGInternal:
      case ElementType::kGMorphogen:
        ++g;
        if (i == 0 || genome.elements[i - 1].type != ElementType::kP) {
          return ::testing::AssertionFailure()
                 << "G at " << i << " does not follow a P";
        }
        break;
      case ElementType::kSIn:
        if (e.channel < 0 || e.channel >= kPaperInputChannels) {
          return ::testing::AssertionFailure()
                 << "S_IN at " << i << " has channel " << e.channel;
        }
        ++inputs[static_cast<size_t>(e.channel)];
        break;
      case ElementType::kSOut:
        if (e.channel < 0 || e.channel >= kOutputChannels) {
          return ::testing::AssertionFailure()
                 << "S_OUT at " << i << " has channel " << e.channel;
        }
        ++outputs[static_cast<size_t>(e.channel)];
        break;
      default:
        return ::testing::AssertionFailure() << "unknown type at " << i;
    }
  }
  if (p != units || g != units) {
    return ::testing::AssertionFailure()
           << p << " P and " << g << " G elements, want " << units << " each";
  }
  for (int c = 0; c < kPaperInputChannels; ++c) {
    if (inputs[static_cast<size_t>(c)] != 1) {
      return ::testing::AssertionFailure()
             << inputs[static_cast<size_t>(c)] << " S_IN of channel "
             << InputChannelName(c);
    }
  }
  for (int c = 0; c < kOutputChannels; ++c) {
    if (outputs[static_cast<size_t>(c)] != 1) {
      return ::testing::AssertionFailure()
             << outputs[static_cast<size_t>(c)] << " S_OUT of channel "
             << OutputChannelName(c);
    }
  }
  return ::testing::AssertionSuccess();
}

TEST(RandomGenomeTest, HasTenUnitsAndOneSElementPerChannel) {
  for (uint64_t individual = 0; individual < 50; ++individual) {
    const Genome genome = Random(1, individual);
    EXPECT_EQ(genome.elements.size(), 30u);
    EXPECT_EQ(Count(genome, ElementType::kP), 10);
    EXPECT_EQ(Count(genome, ElementType::kSIn), kPaperInputChannels);
    EXPECT_EQ(Count(genome, ElementType::kSOut), kOutputChannels);
    EXPECT_TRUE(HasInitialStructure(genome, 10)) << "individual " << individual;
  }
}

TEST(RandomGenomeTest, PassesValidation) {
  for (uint64_t individual = 0; individual < 50; ++individual) {
    const Status status = ValidateGenome(Random(2, individual));
    EXPECT_TRUE(status.ok()) << status.ToString();
  }
}

TEST(RandomGenomeTest, CoordinatesAreInZeroToTen) {
  for (uint64_t individual = 0; individual < 50; ++individual) {
    for (const Element& e : Random(3, individual).elements) {
      EXPECT_GE(e.x, 0.0);
      EXPECT_LT(e.x, 10.0);
      EXPECT_GE(e.y, 0.0);
      EXPECT_LT(e.y, 10.0);
    }
  }
}

TEST(RandomGenomeTest, CoordinateMaxScalesCoordinates) {
  RandomStream stream(3, 0, StreamPurpose::kRandomGenome);
  double largest = 0.0;
  for (const Element& e : RandomGenome(stream, 10, 0.5).elements) {
    EXPECT_GE(e.x, 0.0);
    EXPECT_LT(e.x, 0.5);
    EXPECT_GE(e.y, 0.0);
    EXPECT_LT(e.y, 0.5);
    largest = e.x > largest ? e.x : largest;
  }
  EXPECT_GT(largest, 0.25);
}

TEST(RandomGenomeTest, SignsAreBothPlusAndMinusOne) {
  int plus = 0;
  int minus = 0;
  for (uint64_t individual = 0; individual < 10; ++individual) {
    for (const Element& e : Random(4, individual).elements) {
      ASSERT_TRUE(e.sign == 1 || e.sign == -1) << e.sign;
      plus += e.sign == 1;
      minus += e.sign == -1;
    }
  }
  // 300 fair coins.
  EXPECT_GT(plus, 100);
  EXPECT_GT(minus, 100);
}

TEST(RandomGenomeTest, BothFactorTypesAppear) {
  int internal = 0;
  int morphogen = 0;
  for (uint64_t individual = 0; individual < 10; ++individual) {
    const Genome genome = Random(5, individual);
    internal += Count(genome, ElementType::kGInternal);
    morphogen += Count(genome, ElementType::kGMorphogen);
  }
  // 100 fair coins.
  EXPECT_EQ(internal + morphogen, 100);
  EXPECT_GT(internal, 25);
  EXPECT_GT(morphogen, 25);
}

TEST(RandomGenomeTest, OrderOfUnitsAndSElementsVaries) {
  // The units and S elements are shuffled: over many genomes each kind of
  // element is sometimes first and sometimes last.
  int s_first = 0;
  int p_first = 0;
  int s_last = 0;
  int g_last = 0;
  for (uint64_t individual = 0; individual < 100; ++individual) {
    const Genome genome = Random(6, individual);
    const Element& first = genome.elements.front();
    const Element& last = genome.elements.back();
    p_first += first.type == ElementType::kP;
    s_first +=
        first.type == ElementType::kSIn || first.type == ElementType::kSOut;
    g_last += last.IsG();
    s_last += last.type == ElementType::kSIn || last.type == ElementType::kSOut;
  }
  EXPECT_GT(p_first, 10);
  EXPECT_GT(s_first, 10);
  EXPECT_GT(g_last, 10);
  EXPECT_GT(s_last, 10);
}

TEST(RandomGenomeTest, SameStreamKeyGivesSameGenome) {
  EXPECT_EQ(Random(7, 3), Random(7, 3));
}

TEST(RandomGenomeTest, DifferentKeysGiveDifferentGenomes) {
  const Genome genome = Random(8, 3);
  EXPECT_NE(Random(9, 3), genome);  // Another seed.
  EXPECT_NE(Random(8, 4), genome);  // Another individual.
}

TEST(RandomGenomeTest, ZeroUnitsGivesOnlyTheSElements) {
  const Genome genome = Random(10, 0, 0);
  EXPECT_EQ(genome.elements.size(),
            static_cast<size_t>(kPaperInputChannels + kOutputChannels));
  EXPECT_TRUE(HasInitialStructure(genome, 0));
  EXPECT_TRUE(ValidateGenome(genome).ok());
}

TEST(RandomGenomeTest, OtherUnitCountsKeepTheStructure) {
  for (int units : {1, 3, 40}) {
    EXPECT_TRUE(HasInitialStructure(Random(11, 0, units), units))
        << units << " units";
  }
}

// With guidance, the paper's genome from the same stream plus one CHEMICAL
// S_IN, inserted between units and S elements (docs/model.md §10.2).
TEST(RandomGenomeTest, ChemicalAddsOneInputToThePaperGenome) {
  int at_start = 0, at_end = 0;
  std::vector<int> positions;
  for (uint64_t individual = 0; individual < 200; ++individual) {
    RandomStream stream(12, individual, StreamPurpose::kRandomGenome);
    const Genome genome = RandomGenome(stream, 10, 10.0, /*chemical=*/true);
    ASSERT_TRUE(ValidateGenome(genome).ok());
    const Genome paper = Random(12, individual);
    ASSERT_EQ(genome.elements.size(), paper.elements.size() + 1);
    int chemical = -1;
    for (size_t k = 0; k < genome.elements.size(); ++k) {
      const Element& e = genome.elements[k];
      if (e.type == ElementType::kSIn &&
          e.channel == static_cast<int>(InputChannel::kChemical)) {
        ASSERT_EQ(chemical, -1) << "two CHEMICAL elements";
        chemical = static_cast<int>(k);
      }
    }
    ASSERT_GE(chemical, 0);
    Genome without = genome;
    without.elements.erase(without.elements.begin() + chemical);
    EXPECT_EQ(without, paper);
    // Never between a unit's P and its G.
    if (chemical > 0) {
      EXPECT_NE(genome.elements[chemical - 1].type, ElementType::kP);
    }
    const Element& e = genome.elements[chemical];
    EXPECT_TRUE(e.x >= 0.0 && e.x < 10.0 && e.y >= 0.0 && e.y < 10.0);
    at_start += chemical == 0;
    at_end += chemical == static_cast<int>(paper.elements.size());
    positions.push_back(chemical);
  }
  std::sort(positions.begin(), positions.end());
  positions.erase(std::unique(positions.begin(), positions.end()),
                  positions.end());
  EXPECT_GT(positions.size(), 10u);  // Anywhere, not one fixed place.
  EXPECT_GT(at_start + at_end, 0);   // 2 of 21 boundaries: about 19 of 200.
}

TEST(RandomGenomeTest, WithoutChemicalNoElementHasTheChemicalChannel) {
  for (uint64_t individual = 0; individual < 50; ++individual) {
    for (const Element& e : Random(13, individual).elements) {
      EXPECT_FALSE(e.type == ElementType::kSIn &&
                   e.channel == static_cast<int>(InputChannel::kChemical));
    }
  }
}

}  // namespace
}  // namespace animat
