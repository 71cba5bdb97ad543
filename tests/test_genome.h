// A genome of tests/data/genomes, and a short model configuration, for the
// tests that evaluate one.
#ifndef ANIMAT_TESTS_TEST_GENOME_H_
#define ANIMAT_TESTS_TEST_GENOME_H_

#include <gtest/gtest.h>

#include <string>

#include "common/evaluation/model_config.h"
#include "common/genome/genome_proto.h"
#include "common/io/proto_file.h"
#include "tests/test_util.h"

namespace animat::testing {

// tests/data/genomes/`name`, read and checked; a failed read or an invalid
// genome fails the calling test (non-fatally) and gives an empty genome.
inline Genome LoadGenome(const std::string& name) {
  v1::Genome message;
  Status status = ReadProtoFile(TestData("genomes/" + name), &message);
  EXPECT_TRUE(status.ok()) << status.ToString();
  Result<Genome> genome = GenomeFromProto(message);
  EXPECT_TRUE(genome.ok()) << genome.status().ToString();
  return genome.ok() ? *genome : Genome{};
}

// The default model with a short motion phase (300 steps): the statuses,
// and whether two evaluations agree, do not depend on the motion's length.
inline ModelConfig ShortConfig() {
  ModelConfig config;
  config.evaluation.motion_steps = 300;
  return config;
}

}  // namespace animat::testing

#endif  // ANIMAT_TESTS_TEST_GENOME_H_
