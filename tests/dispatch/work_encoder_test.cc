// Work envelopes assembled from items serialised once (master/work_encoder):
// byte for byte what protobuf gives for the same messages, so workers read
// them as any other.
#include "master/dispatch/work_encoder.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "animat/v1/protocol.pb.h"
#include "common/base/rng.h"
#include "common/genome/genome_proto.h"
#include "common/genome/random_genome.h"
#include "common/protocol/genome_wire.h"
#include "common/protocol/protocol.h"

namespace animat {
namespace {

std::vector<v1::Genome> Genomes(int count) {
  std::vector<v1::Genome> genomes;
  for (int i = 0; i < count; ++i) {
    RandomStream stream(31, static_cast<uint64_t>(i),
                        StreamPurpose::kRandomGenome);
    genomes.push_back(GenomeToProto(RandomGenome(stream)));
  }
  return genomes;
}

v1::WorkItem Item(uint64_t individual, const v1::Genome& genome) {
  v1::WorkItem item;
  item.set_individual(individual);
  *item.mutable_genome() = genome;
  item.set_genome_hash(protocol::GenomeHash(genome));
  return item;
}

TEST(WorkEncoderTest, SerializedGenomeHashIsTheGenomeHash) {
  for (const v1::Genome& genome : Genomes(5)) {
    const protocol::SerializedGenome serialized =
        protocol::SerializeGenome(genome);
    EXPECT_EQ(serialized.hash, protocol::GenomeHash(genome));
    // The same bytes as protobuf's usual serialisation (a genome has no
    // maps), so stores may hold either.
    EXPECT_EQ(serialized.bytes, genome.SerializeAsString());
    v1::Genome parsed;
    ASSERT_TRUE(parsed.ParseFromString(serialized.bytes));
    EXPECT_EQ(parsed.SerializeAsString(), genome.SerializeAsString());
  }
}

TEST(WorkEncoderTest, ItemIsTheWorkItemsSerialization) {
  const std::vector<v1::Genome> genomes = Genomes(4);
  // Individual 0 leaves its field out, as protobuf does; an empty genome
  // is still present; large ids take long varints.
  const std::vector<uint64_t> ids = {0, 1, 300, uint64_t{1} << 63};
  for (size_t i = 0; i < ids.size(); ++i) {
    const std::string encoded =
        EncodeWorkItem(ids[i], protocol::SerializeGenome(genomes[i]));
    EXPECT_EQ(encoded, Item(ids[i], genomes[i]).SerializeAsString())
        << "individual " << ids[i];
  }
  EXPECT_EQ(EncodeWorkItem(7, protocol::SerializeGenome(v1::Genome())),
            Item(7, v1::Genome()).SerializeAsString());
}

TEST(WorkEncoderTest, EnvelopeIsEncodeOfTheSameWork) {
  const std::vector<v1::Genome> genomes = Genomes(40);
  const uint64_t config_hash = 0x0123456789abcdefull;
  for (int count : {0, 1, 2, 40}) {
    WorkEncoder encoder(config_hash);
    v1::Envelope envelope;
    envelope.mutable_work()->set_config_hash(config_hash);
    size_t item_bytes = 0;
    for (int i = 0; i < count; ++i) {
      const uint64_t id = 1000 + static_cast<uint64_t>(i);
      const std::string item = EncodeWorkItem(
          id, protocol::SerializeGenome(genomes[static_cast<size_t>(i)]));
      item_bytes += item.size();
      encoder.Add(item);
      *envelope.mutable_work()->add_items() =
          Item(id, genomes[static_cast<size_t>(i)]);
    }
    EXPECT_EQ(encoder.items(), count);
    EXPECT_EQ(encoder.item_bytes(), item_bytes);
    const std::string bytes = encoder.Finish();
    EXPECT_EQ(bytes, protocol::Encode(envelope)) << count << " items";
    Result<v1::Envelope> decoded = protocol::Decode(bytes);
    ASSERT_TRUE(decoded.ok()) << decoded.status().ToString();
    ASSERT_TRUE(decoded->has_work());
    EXPECT_EQ(decoded->work().config_hash(), config_hash);
    EXPECT_EQ(decoded->work().items_size(), count);
  }
}

TEST(WorkEncoderTest, ACarriedConfigIsEncodeOfTheSameWork) {
  const std::vector<v1::Genome> genomes = Genomes(3);
  v1::Config config;
  config.mutable_physics()->set_drag_normal(10);
  config.mutable_development()->set_max_cells(8);
  const uint64_t hash = protocol::ConfigHash(config);
  WorkEncoder encoder(hash);
  encoder.SetConfig(config.SerializeAsString());
  v1::Envelope envelope;
  envelope.mutable_work()->set_config_hash(hash);
  for (size_t i = 0; i < genomes.size(); ++i) {
    encoder.Add(EncodeWorkItem(i + 1, protocol::SerializeGenome(genomes[i])));
    *envelope.mutable_work()->add_items() = Item(i + 1, genomes[i]);
  }
  *envelope.mutable_work()->mutable_config() = config;
  EXPECT_EQ(encoder.Finish(), protocol::Encode(envelope));
  // Not carried again unless set again.
  envelope.mutable_work()->clear_config();
  envelope.mutable_work()->clear_items();
  EXPECT_EQ(encoder.Finish(), protocol::Encode(envelope));
}

TEST(WorkEncoderTest, FinishEmptiesTheEncoder) {
  const std::vector<v1::Genome> genomes = Genomes(1);
  WorkEncoder encoder(5);
  encoder.Add(EncodeWorkItem(1, protocol::SerializeGenome(genomes[0])));
  (void)encoder.Finish();
  EXPECT_EQ(encoder.items(), 0);
  EXPECT_EQ(encoder.item_bytes(), 0u);
  v1::Envelope empty;
  empty.mutable_work()->set_config_hash(5);
  EXPECT_EQ(encoder.Finish(), protocol::Encode(empty));
}

}  // namespace
}  // namespace animat
