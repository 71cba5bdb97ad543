// protocol::SerializeGenome(const Genome&) writes exactly the bytes, hash
// and length that serialising GenomeToProto(genome) gives, for random
// genomes and for the values where protobuf's rules bite (zeros, -0.0,
// negative int32s, defaults left out).
#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "common/base/rng.h"
#include "common/genome/genome.h"
#include "common/genome/genome_proto.h"
#include "common/genome/random_genome.h"
#include "common/protocol/genome_wire.h"

namespace animat {
namespace {

void ExpectSameAsProtobuf(const Genome& genome) {
  const v1::Genome message = GenomeToProto(genome);
  const protocol::SerializedGenome expected =
      protocol::SerializeGenome(message);
  const protocol::SerializedGenome direct = protocol::SerializeGenome(genome);
  EXPECT_EQ(direct.bytes, expected.bytes);
  EXPECT_EQ(direct.bytes, message.SerializeAsString());
  EXPECT_EQ(direct.hash, expected.hash);
  EXPECT_EQ(direct.hash, protocol::GenomeHash(message));
  EXPECT_EQ(direct.elements, message.elements_size());
  EXPECT_EQ(direct.elements, expected.elements);
}

TEST(GenomeEncoderTest, RandomGenomesOfEverySizeMatchProtobuf) {
  for (int i = 0; i < 300; ++i) {
    RandomStream stream(7, static_cast<uint64_t>(i),
                        StreamPurpose::kRandomGenome);
    const Genome genome = RandomGenome(stream, 1 + i % 40);
    SCOPED_TRACE("genome " + std::to_string(i));
    ExpectSameAsProtobuf(genome);
  }
}

// Guidance genomes carry CHEMICAL (docs/model.md §10.2), whose proto
// number (11) does not follow UNIFORM's.
TEST(GenomeEncoderTest, ChemicalInputsMatchProtobuf) {
  for (int i = 0; i < 50; ++i) {
    RandomStream stream(8, static_cast<uint64_t>(i),
                        StreamPurpose::kRandomGenome);
    const Genome genome = RandomGenome(stream, 1 + i % 20, 10.0, true);
    SCOPED_TRACE("genome " + std::to_string(i));
    ExpectSameAsProtobuf(genome);
  }
}

TEST(GenomeEncoderTest, EmptyGenomeIsNoBytes) {
  ExpectSameAsProtobuf(Genome());
  EXPECT_TRUE(protocol::SerializeGenome(Genome()).bytes.empty());
}

TEST(GenomeEncoderTest, ZerosNegativesAndExtremesMatchProtobuf) {
  const double values[] = {0.0,
                           -0.0,
                           1.0,
                           -1.0,
                           10.0,
                           std::numeric_limits<double>::denorm_min(),
                           -std::numeric_limits<double>::max(),
                           std::numeric_limits<double>::infinity(),
                           std::numeric_limits<double>::quiet_NaN()};
  const ElementType types[] = {ElementType::kP, ElementType::kGInternal,
                               ElementType::kGMorphogen, ElementType::kSIn,
                               ElementType::kSOut};
  Genome genome;
  int k = 0;
  for (ElementType type : types) {
    for (double x : values) {
      for (double y : {0.0, -0.0, 3.5}) {
        Element e;
        e.type = type;
        e.sign = (k % 3 == 0) ? -1 : 1;
        e.x = x;
        e.y = y;
        if (type == ElementType::kSIn) e.channel = k % kInputChannels;
        if (type == ElementType::kSOut) e.channel = k % 6;
        genome.elements.push_back(e);
        ++k;
      }
    }
  }
  ExpectSameAsProtobuf(genome);
  // Values no valid genome holds are still written as protobuf would: a
  // sign of 0 (left out), large signs, a channel that maps to 0 or below.
  Genome odd;
  for (int sign : {0, 2, -7, std::numeric_limits<int>::min(),
                   std::numeric_limits<int>::max()}) {
    Element e;
    e.sign = sign;
    odd.elements.push_back(e);
  }
  Element none;
  none.type = ElementType::kSIn;
  none.channel = -1;  // Channel value 0: left out.
  odd.elements.push_back(none);
  Element negative;
  negative.type = ElementType::kSOut;
  negative.channel = -200;  // A negative enum value: 10 bytes.
  odd.elements.push_back(negative);
  ExpectSameAsProtobuf(odd);
}

}  // namespace
}  // namespace animat
