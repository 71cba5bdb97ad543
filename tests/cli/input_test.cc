// End-to-end tests of what the tools make of bad input (ids, empty and
// junk files, the wrong kind of configuration) and of what they print
// about themselves (--version, config defaults, numbers in messages).
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "animat/v1/evolution.pb.h"
#include "common/evaluation/model_config.h"
#include "common/io/proto_file.h"
#include "common/protocol/protocol.h"
#include "master/evolution/evolution_params.h"
#include "tests/cli/run_animat.h"
#include "tests/test_util.h"

namespace animat {
namespace {

using ::animat::testing::Animat;
using ::animat::testing::Outcome;

std::string Temp(const std::string& name) {
  return ::testing::TempDir() + "/animat-input-" + name;
}

TEST(CliInputTest, NumbersInMessagesAreShortest) {
  const std::string config = Temp("dt.txtpb");
  ASSERT_TRUE(WriteFile(config, "physics { dt: -0.7 }\n").ok());
  const Outcome run =
      Animat("simulate --genome " + testing::TestData("genomes/example.json") +
             " --config " + config);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.output.find("physics.dt: must be finite and > 0, got -0.7\n"),
            std::string::npos)
      << run.output;
}

}  // namespace
}  // namespace animat
