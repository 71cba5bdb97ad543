// A genome of tests/data/genomes for the tests that evaluate one.
#ifndef ANIMAT_TESTS_TEST_GENOME_H_
#define ANIMAT_TESTS_TEST_GENOME_H_

#include <gtest/gtest.h>

#include <string>

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

}  // namespace animat::testing

#endif  // ANIMAT_TESTS_TEST_GENOME_H_
