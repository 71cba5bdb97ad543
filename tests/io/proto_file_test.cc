#include "common/io/proto_file.h"

#include <stdlib.h>  // mkdtemp

#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include <google/protobuf/util/message_differencer.h>
#include <gtest/gtest.h>

#include "animat/v1/config.pb.h"
#include "animat/v1/genome.pb.h"

namespace animat {
namespace {

using google::protobuf::util::MessageDifferencer;

// Checks that `status` has `code` and a message starting with `prefix` and
// containing each of `parts`.
::testing::AssertionResult IsError(
    const Status& status, StatusCode code, std::string_view prefix,
    std::initializer_list<std::string_view> parts = {}) {
  const std::string& m = status.message();
  bool good = status.code() == code && m.compare(0, prefix.size(), prefix) == 0;
  for (std::string_view part : parts) {
    good = good && m.find(part) != std::string::npos;
  }
  if (good) return ::testing::AssertionSuccess();
  ::testing::AssertionResult failure = ::testing::AssertionFailure();
  failure << "got \"" << status.ToString() << "\", want code "
          << static_cast<int>(code) << " and a message starting with \""
          << prefix << "\"";
  for (std::string_view part : parts) {
    failure << " containing \"" << part << "\"";
  }
  return failure;
}

// A genome with every field set somewhere, and some at their defaults.
v1::Genome SampleGenome() {
  v1::Genome genome;
  v1::Element* e = genome.add_elements();
  e->set_type(v1::Element::S_IN);
  e->set_sign(-1);
  e->set_x(1.5);
  e->set_y(0.1);  // Not exact in binary: checks the printed precision.
  e->set_channel(v1::Element::UNIFORM);
  e = genome.add_elements();
  e->set_type(v1::Element::G_MORPHOGEN);
  e->set_sign(1);
  e->set_x(9.999999999999998);
  e->set_y(-2.5e-7);
  e = genome.add_elements();
  e->set_type(v1::Element::S_OUT);
  e->set_sign(1);
  e->set_channel(v1::Element::CONTRACT);
  return genome;
}

// A configuration with fields of every kind, including an optional field
// set to its type's default (which must survive as "present").
v1::Config SampleConfig() {
  v1::Config config;
  config.mutable_grn()->set_weight_max(12.5);
  config.mutable_grn()->set_dt(0.05);
  config.mutable_development()->set_max_cells(16);
  config.mutable_development()->set_divide_threshold(0.0);
  config.mutable_signals()->set_max_delay(127);
  config.mutable_physics()->set_drag_tangential(0.005);
  config.mutable_evaluation()->set_max_coordinate(1e6);
  return config;
}

class ProtoFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string base = ::testing::TempDir();
    if (base.empty() || base.back() != '/') base += '/';
    std::string pattern = base + "animat_io_test_XXXXXX";
    ASSERT_NE(mkdtemp(pattern.data()), nullptr) << pattern;
    dir_ = pattern;
  }

  void TearDown() override {
    std::error_code ignored;
    std::filesystem::remove_all(dir_, ignored);
  }

  std::string Path(const std::string& name) const { return dir_ + "/" + name; }

  // Writes `contents` to the file `name` of the test's directory and
  // returns its path.
  std::string Write(const std::string& name, const std::string& contents) {
    const std::string path = Path(name);
    std::ofstream out(path, std::ios::binary);
    out << contents;
    out.close();
    EXPECT_TRUE(out.good()) << path;
    return path;
  }

  std::string dir_;
};

TEST_F(ProtoFileTest, ReadsJsonWithEnumNames) {
  const std::string path = Write("genome.json", R"({
    "elements": [
      {"type": "S_IN", "sign": -1, "x": 1.5, "y": 2, "channel": "UNIFORM"},
      {"type": "G_MORPHOGEN", "sign": 1, "x": 0.25, "y": 7.75}
    ]
  })");
  v1::Genome genome;
  const Status status = ReadProtoFile(path, &genome);
  ASSERT_TRUE(status.ok()) << status.ToString();
  ASSERT_EQ(genome.elements_size(), 2);
  EXPECT_EQ(genome.elements(0).type(), v1::Element::S_IN);
  EXPECT_EQ(genome.elements(0).sign(), -1);
  EXPECT_EQ(genome.elements(0).x(), 1.5);
  EXPECT_EQ(genome.elements(0).y(), 2.0);
  EXPECT_EQ(genome.elements(0).channel(), v1::Element::UNIFORM);
  EXPECT_EQ(genome.elements(1).type(), v1::Element::G_MORPHOGEN);
  EXPECT_EQ(genome.elements(1).channel(), v1::Element::CHANNEL_NONE);
}

TEST_F(ProtoFileTest, ReadsJsonConfigWithProtoOrCamelCaseNames) {
  const std::string path = Write("config.json", R"({
    "development": {"max_cells": 16, "divideThreshold": 0.75},
    "physics": {"dragTangential": 0.01}
  })");
  v1::Config config;
  const Status status = ReadProtoFile(path, &config);
  ASSERT_TRUE(status.ok()) << status.ToString();
  EXPECT_EQ(config.development().max_cells(), 16);
  EXPECT_EQ(config.development().divide_threshold(), 0.75);
  EXPECT_EQ(config.physics().drag_tangential(), 0.01);
  EXPECT_FALSE(config.development().has_steps());
  EXPECT_FALSE(config.has_grn());
}

TEST_F(ProtoFileTest, ReadsTextFormat) {
  const std::string path = Write("genome.txtpb", R"(# A comment.
elements {
  type: S_OUT
  sign: -1
  x: 3.25
  y: 4
  channel: DIVIDE
}
elements { type: P sign: 1 }
)");
  v1::Genome genome;
  const Status status = ReadProtoFile(path, &genome);
  ASSERT_TRUE(status.ok()) << status.ToString();
  ASSERT_EQ(genome.elements_size(), 2);
  EXPECT_EQ(genome.elements(0).type(), v1::Element::S_OUT);
  EXPECT_EQ(genome.elements(0).sign(), -1);
  EXPECT_EQ(genome.elements(0).x(), 3.25);
  EXPECT_EQ(genome.elements(0).y(), 4.0);
  EXPECT_EQ(genome.elements(0).channel(), v1::Element::DIVIDE);
  EXPECT_EQ(genome.elements(1).type(), v1::Element::P);
}

TEST_F(ProtoFileTest, ReadsTextFormatConfig) {
  const std::string path = Write("config.textproto",
                                 "grn { cutoff: 2.5 }\n"
                                 "evaluation { motion_steps: 100 }\n");
  v1::Config config;
  const Status status = ReadProtoFile(path, &config);
  ASSERT_TRUE(status.ok()) << status.ToString();
  EXPECT_EQ(config.grn().cutoff(), 2.5);
  EXPECT_EQ(config.evaluation().motion_steps(), 100);
  EXPECT_FALSE(config.grn().has_weight_max());
}

TEST_F(ProtoFileTest, ExtensionChoosesFormat) {
  EXPECT_EQ(*ProtoFormatForPath("a/b.json"), ProtoFormat::kJson);
  EXPECT_EQ(*ProtoFormatForPath("b.txtpb"), ProtoFormat::kText);
  EXPECT_EQ(*ProtoFormatForPath("b.textproto"), ProtoFormat::kText);
  EXPECT_EQ(*ProtoFormatForPath("b.pbtxt"), ProtoFormat::kText);
  EXPECT_EQ(*ProtoFormatForPath("b.binpb"), ProtoFormat::kBinary);
  EXPECT_EQ(*ProtoFormatForPath("b.pb"), ProtoFormat::kBinary);
}

TEST_F(ProtoFileTest, JsonInTextFormatFileFails) {
  const std::string path =
      Write("genome.txtpb", R"({"elements": [{"type": "P", "sign": 1}]})");
  v1::Genome genome;
  EXPECT_TRUE(IsError(ReadProtoFile(path, &genome),
                      StatusCode::kInvalidArgument, path + ":1:"));
}

TEST_F(ProtoFileTest, TextFormatInJsonFileFails) {
  const std::string path = Write("genome.json", "elements { type: P }\n");
  v1::Genome genome;
  EXPECT_TRUE(IsError(ReadProtoFile(path, &genome),
                      StatusCode::kInvalidArgument, path + ": "));
}

TEST_F(ProtoFileTest, UnknownExtensionFailsNamingAcceptedOnes) {
  const std::string path = Write("genome.yaml", "elements: []\n");
  v1::Genome genome;
  EXPECT_TRUE(IsError(ReadProtoFile(path, &genome),
                      StatusCode::kInvalidArgument, path + ": ",
                      {".json", ".txtpb", ".binpb"}));
  EXPECT_TRUE(IsError(ProtoFormatForPath("genome").status(),
                      StatusCode::kInvalidArgument,
                      "genome: ", {".json", ".txtpb", ".binpb"}));
  // Writing is refused too, and creates no file.
  const std::string out = Path("out.yml");
  EXPECT_TRUE(IsError(WriteProtoFile(out, genome), StatusCode::kInvalidArgument,
                      out + ": "));
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST_F(ProtoFileTest, MissingFileIsNotFoundNamingPath) {
  const std::string path = Path("absent.json");
  v1::Genome genome;
  EXPECT_TRUE(IsError(ReadProtoFile(path, &genome), StatusCode::kNotFound,
                      path + ": "));
  EXPECT_TRUE(IsError(ReadFile(path).status(), StatusCode::kNotFound, path));
}

TEST_F(ProtoFileTest, JsonErrorNamesFileAndUnknownField) {
  const std::string path =
      Write("genome.json", R"({"elements": [{"type": "P", "sgn": 1}]})");
  v1::Genome genome;
  // protobuf says "(elements[0]) sgn: Cannot find field."
  EXPECT_TRUE(IsError(ReadProtoFile(path, &genome),
                      StatusCode::kInvalidArgument, path + ": ",
                      {"elements[0]", "sgn"}));
}

TEST_F(ProtoFileTest, JsonErrorNamesFileAndMistypedField) {
  const std::string path =
      Write("genome.json", R"({"elements": [{"type": "P", "x": "far away"}]})");
  v1::Genome genome;
  EXPECT_TRUE(IsError(ReadProtoFile(path, &genome),
                      StatusCode::kInvalidArgument, path + ": ",
                      {"elements[0].x", "far away"}));
}

TEST_F(ProtoFileTest, JsonErrorNamesFileAndUnknownEnumName) {
  const std::string path = Write(
      "genome.json", R"({"elements": [{"type": "S_IN", "channel": "LEFT"}]})");
  v1::Genome genome;
  EXPECT_TRUE(IsError(ReadProtoFile(path, &genome),
                      StatusCode::kInvalidArgument, path + ": ",
                      {"elements[0].channel", "LEFT"}));
}

TEST_F(ProtoFileTest, TextErrorNamesFileLineAndColumn) {
  const std::string path = Write("genome.txtpb",
                                 "elements {\n"
                                 "  type: P\n"
                                 "  sgn: 1\n"
                                 "}\n");
  v1::Genome genome;
  const Status status = ReadProtoFile(path, &genome);
  ASSERT_TRUE(
      IsError(status, StatusCode::kInvalidArgument, path + ":3:", {"sgn"}));
  // The column is 1-based, at or just after the unknown name (protobuf
  // reports the token after it: "path:3:6: ...").
  const std::string rest = status.message().substr(path.size() + 3);
  const size_t colon = rest.find(": ");
  ASSERT_NE(colon, std::string::npos) << status.message();
  const int column = std::stoi(rest.substr(0, colon));
  EXPECT_GE(column, 3) << status.message();
  EXPECT_LE(column, 6) << status.message();
}

TEST_F(ProtoFileTest, TextErrorLocatesBadValue) {
  const std::string path = Write("config.txtpb",
                                 "grn {\n"
                                 "  dt: 0.05\n"
                                 "}\n"
                                 "development { max_cells: many }\n");
  v1::Config config;
  EXPECT_TRUE(IsError(ReadProtoFile(path, &config),
                      StatusCode::kInvalidArgument, path + ":4:", {"many"}));
}

TEST_F(ProtoFileTest, MalformedBinaryFails) {
  const std::string path =
      Write("genome.binpb", std::string("\x0a\x05\x08", 3));
  v1::Genome genome;
  EXPECT_TRUE(IsError(ReadProtoFile(path, &genome),
                      StatusCode::kInvalidArgument, path + ": "));
}

TEST_F(ProtoFileTest, ReadReplacesPreviousContents) {
  const std::string path = Write("genome.txtpb", "elements { type: P }\n");
  v1::Genome genome = SampleGenome();
  const Status status = ReadProtoFile(path, &genome);
  ASSERT_TRUE(status.ok()) << status.ToString();
  EXPECT_EQ(genome.elements_size(), 1);
}

TEST_F(ProtoFileTest, WriteThenReadRoundTripsInEveryFormat) {
  for (const char* name :
       {"g.json", "g.txtpb", "g.textproto", "g.pbtxt", "g.binpb", "g.pb"}) {
    const std::string path = Path(name);
    const v1::Genome genome = SampleGenome();
    ASSERT_TRUE(WriteProtoFile(path, genome).ok()) << path;
    v1::Genome genome_back;
    const Status genome_status = ReadProtoFile(path, &genome_back);
    ASSERT_TRUE(genome_status.ok()) << genome_status.ToString();
    EXPECT_TRUE(MessageDifferencer::Equals(genome_back, genome))
        << name << ":\n"
        << genome_back.DebugString();

    const std::string config_path = Path(std::string("config_") + name);
    const v1::Config config = SampleConfig();
    ASSERT_TRUE(WriteProtoFile(config_path, config).ok()) << config_path;
    v1::Config config_back;
    const Status config_status = ReadProtoFile(config_path, &config_back);
    ASSERT_TRUE(config_status.ok()) << config_status.ToString();
    EXPECT_TRUE(MessageDifferencer::Equals(config_back, config))
        << name << ":\n"
        << config_back.DebugString();
    EXPECT_TRUE(config_back.development().has_divide_threshold()) << name;
  }
}

TEST_F(ProtoFileTest, WriteReplacesExistingFile) {
  const std::string path = Write("genome.json", std::string(10000, ' '));
  ASSERT_TRUE(WriteProtoFile(path, v1::Genome()).ok());
  v1::Genome genome = SampleGenome();
  const Status status = ReadProtoFile(path, &genome);
  ASSERT_TRUE(status.ok()) << status.ToString();
  EXPECT_EQ(genome.elements_size(), 0);
}

TEST_F(ProtoFileTest, WriteIntoMissingDirectoryIsIoError) {
  const std::string path = Path("no/such/dir/genome.json");
  EXPECT_TRUE(IsError(WriteProtoFile(path, SampleGenome()),
                      StatusCode::kIoError, path + ": "));
}

TEST(SerializeProtoTest, JsonPrintsFieldsAtDefaultValues) {
  v1::Genome genome;
  v1::Element* e = genome.add_elements();
  e->set_type(v1::Element::P);
  const std::string json = SerializeProto(genome, ProtoFormat::kJson);
  EXPECT_NE(json.find("\"sign\": 0"), std::string::npos) << json;
  EXPECT_NE(json.find("\"x\": 0"), std::string::npos) << json;
  EXPECT_NE(json.find("\"y\": 0"), std::string::npos) << json;
  EXPECT_NE(json.find("\"channel\": \"CHANNEL_NONE\""), std::string::npos)
      << json;
  EXPECT_NE(json.find("\"type\": \"P\""), std::string::npos) << json;
}

TEST(SerializeProtoTest, JsonUsesProtoFieldNames) {
  v1::Config config;
  config.mutable_development()->set_max_cells(16);
  const std::string json = SerializeProto(config, ProtoFormat::kJson);
  EXPECT_NE(json.find("\"max_cells\": 16"), std::string::npos) << json;
  EXPECT_EQ(json.find("maxCells"), std::string::npos) << json;
}

TEST(SerializeProtoTest, ParseProtoInvertsSerializeProto) {
  const v1::Genome genome = SampleGenome();
  for (ProtoFormat format :
       {ProtoFormat::kJson, ProtoFormat::kText, ProtoFormat::kBinary}) {
    v1::Genome back;
    const Status status =
        ParseProto(SerializeProto(genome, format), format, &back);
    ASSERT_TRUE(status.ok()) << status.ToString();
    EXPECT_TRUE(MessageDifferencer::Equals(back, genome))
        << static_cast<int>(format);
  }
}

}  // namespace
}  // namespace animat
