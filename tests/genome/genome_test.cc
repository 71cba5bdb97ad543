#include "common/genome/genome.h"

#include <cmath>
#include <initializer_list>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include <google/protobuf/util/message_differencer.h>
#include <gtest/gtest.h>

#include "animat/v1/genome.pb.h"
#include "common/genome/genome_proto.h"
#include "tests/test_util.h"

namespace animat {
namespace {

// Checks that `status` is an invalid-argument error whose message starts
// with `prefix` and contains each of `parts`.
::testing::AssertionResult IsError(
    const Status& status, std::string_view prefix,
    std::initializer_list<std::string_view> parts = {}) {
  const std::string& m = status.message();
  bool good = status.code() == StatusCode::kInvalidArgument &&
              m.compare(0, prefix.size(), prefix) == 0;
  for (std::string_view part : parts) {
    good = good && m.find(part) != std::string::npos;
  }
  if (good) return ::testing::AssertionSuccess();
  ::testing::AssertionResult failure = ::testing::AssertionFailure();
  failure << "got \"" << status.ToString() << "\", want an invalid argument "
          << "starting with \"" << prefix << "\"";
  for (std::string_view part : parts)
    failure << " containing \"" << part << "\"";
  return failure;
}

// One element of every type and every channel, with varied signs and
// coordinates (negative and non-integer ones too).
v1::Genome EveryKindOfElement() {
  v1::Genome message;
  auto add = [&](v1::Element::Type type, int sign, double x, double y,
                 v1::Element::Channel channel) {
    v1::Element* e = message.add_elements();
    e->set_type(type);
    e->set_sign(sign);
    e->set_x(x);
    e->set_y(y);
    e->set_channel(channel);
  };
  add(v1::Element::P, 1, 0.5, 9.75, v1::Element::CHANNEL_NONE);
  add(v1::Element::G_INTERNAL, -1, 1e-300, -3.25, v1::Element::CHANNEL_NONE);
  add(v1::Element::G_MORPHOGEN, 1, 123.456, 0.0, v1::Element::CHANNEL_NONE);
  const v1::Element::Channel inputs[] = {
      v1::Element::MATERNAL_0, v1::Element::MATERNAL_1, v1::Element::MATERNAL_2,
      v1::Element::UNIFORM};
  for (v1::Element::Channel c : inputs) {
    add(v1::Element::S_IN, -1, 0.1 * static_cast<int>(c), 7.0, c);
  }
  const v1::Element::Channel outputs[] = {
      v1::Element::DIVIDE, v1::Element::ROTATE_LEFT, v1::Element::ROTATE_RIGHT,
      v1::Element::SIZE,   v1::Element::EXPAND,      v1::Element::CONTRACT};
  for (v1::Element::Channel c : outputs) {
    add(v1::Element::S_OUT, 1, 2.0, 0.3 * static_cast<int>(c), c);
  }
  return message;
}

v1::Genome OneElement(v1::Element::Type type, int sign,
                      v1::Element::Channel channel) {
  v1::Genome message;
  v1::Element* e = message.add_elements();
  e->set_type(type);
  e->set_sign(sign);
  e->set_x(1.0);
  e->set_y(2.0);
  e->set_channel(channel);
  return message;
}

// A valid genome of n P elements.
v1::Genome PElements(int n) {
  v1::Genome message;
  for (int i = 0; i < n; ++i) {
    v1::Element* e = message.add_elements();
    e->set_type(v1::Element::P);
    e->set_sign(1);
  }
  return message;
}

// `message` with a valid P element in front of each of its elements, so
// that an error in the original element i is reported at index 2i + 1.
v1::Genome Interleaved(const v1::Genome& message) {
  v1::Genome out;
  for (const v1::Element& e : message.elements()) {
    *out.add_elements() = PElements(1).elements(0);
    *out.add_elements() = e;
  }
  return out;
}

// The error of GenomeFromProto for `message` put at index 1 of a genome.
Status ErrorAtIndexOne(const v1::Genome& message) {
  const Result<Genome> genome = GenomeFromProto(Interleaved(message));
  return genome.ok() ? Status::Ok() : genome.status();
}

TEST(GenomeProtoTest, RoundTripsEveryKindOfElement) {
  const v1::Genome message = EveryKindOfElement();
  const Result<Genome> genome = GenomeFromProto(message);
  ASSERT_TRUE(genome.ok()) << genome.status().ToString();
  ASSERT_EQ(genome->elements.size(), 13u);
  EXPECT_TRUE(google::protobuf::util::MessageDifferencer::Equals(
      GenomeToProto(*genome), message))
      << GenomeToProto(*genome).DebugString();
}

TEST(GenomeProtoTest, ConvertsFieldsToTheirGenomeValues) {
  const Result<Genome> genome = GenomeFromProto(EveryKindOfElement());
  ASSERT_TRUE(genome.ok()) << genome.status().ToString();
  const std::vector<Element>& e = genome->elements;
  EXPECT_EQ(e[0], (Element{ElementType::kP, 1, 0.5, 9.75, -1}));
  EXPECT_EQ(e[1], (Element{ElementType::kGInternal, -1, 1e-300, -3.25, -1}));
  EXPECT_EQ(e[2], (Element{ElementType::kGMorphogen, 1, 123.456, 0.0, -1}));
  for (int c = 0; c < kPaperInputChannels; ++c) {
    EXPECT_EQ(e[3 + c].type, ElementType::kSIn);
    EXPECT_EQ(e[3 + c].channel, c);
  }
  EXPECT_EQ(e[6].channel, static_cast<int>(InputChannel::kUniform));
  for (int c = 0; c < kOutputChannels; ++c) {
    EXPECT_EQ(e[7 + c].type, ElementType::kSOut);
    EXPECT_EQ(e[7 + c].channel, c);
  }
  EXPECT_EQ(e[12].channel, static_cast<int>(OutputChannel::kContract));
}

TEST(GenomeProtoTest, RoundTripsFromGenome) {
  Genome genome;
  genome.elements = {
      {ElementType::kSOut, -1, -0.0, 5.5, 3},
      {ElementType::kP, 1, 1.0, 2.0, -1},
      {ElementType::kGMorphogen, -1, 3.0, 4.0, -1},
      {ElementType::kSIn, 1, 9.999, 0.001, 2},
  };
  ASSERT_TRUE(ValidateGenome(genome).ok());
  const Result<Genome> back = GenomeFromProto(GenomeToProto(genome));
  ASSERT_TRUE(back.ok()) << back.status().ToString();
  EXPECT_EQ(*back, genome);
  EXPECT_TRUE(std::signbit(back->elements[0].x));
}

TEST(GenomeProtoTest, EmptyGenomeIsValid) {
  const Result<Genome> genome = GenomeFromProto(v1::Genome());
  ASSERT_TRUE(genome.ok()) << genome.status().ToString();
  EXPECT_TRUE(genome->elements.empty());
  EXPECT_EQ(GenomeToProto(Genome()).elements_size(), 0);
  EXPECT_TRUE(ValidateGenome(Genome()).ok());
}

TEST(GenomeProtoTest, RejectsSignZero) {
  EXPECT_TRUE(IsError(
      ErrorAtIndexOne(OneElement(v1::Element::P, 0, v1::Element::CHANNEL_NONE)),
      "elements[1].sign:", {"got 0"}));
}

TEST(GenomeProtoTest, RejectsSignTwo) {
  EXPECT_TRUE(IsError(ErrorAtIndexOne(OneElement(v1::Element::G_INTERNAL, 2,
                                                 v1::Element::CHANNEL_NONE)),
                      "elements[1].sign:", {"got 2"}));
}

TEST(GenomeProtoTest, RejectsNonFiniteCoordinates) {
  testing::FpTrapsOff traps_off;
  const double values[] = {std::numeric_limits<double>::quiet_NaN(),
                           std::numeric_limits<double>::infinity(),
                           -std::numeric_limits<double>::infinity()};
  for (double value : values) {
    v1::Genome message =
        OneElement(v1::Element::P, 1, v1::Element::CHANNEL_NONE);
    message.mutable_elements(0)->set_x(value);
    EXPECT_TRUE(IsError(ErrorAtIndexOne(message), "elements[1]", {"finite"}))
        << "x = " << value;

    message.mutable_elements(0)->set_x(1.0);
    message.mutable_elements(0)->set_y(value);
    EXPECT_TRUE(IsError(ErrorAtIndexOne(message), "elements[1]", {"finite"}))
        << "y = " << value;
  }
}

TEST(GenomeProtoTest, RejectsInputWithOutputChannel) {
  EXPECT_TRUE(IsError(
      ErrorAtIndexOne(OneElement(v1::Element::S_IN, 1, v1::Element::DIVIDE)),
      "elements[1].channel:", {"input channel", "got DIVIDE"}));
}

TEST(GenomeProtoTest, RejectsInputWithoutChannel) {
  EXPECT_TRUE(
      IsError(ErrorAtIndexOne(
                  OneElement(v1::Element::S_IN, 1, v1::Element::CHANNEL_NONE)),
              "elements[1].channel:", {"input channel", "got CHANNEL_NONE"}));
}

TEST(GenomeProtoTest, RejectsOutputWithInputChannel) {
  EXPECT_TRUE(IsError(
      ErrorAtIndexOne(OneElement(v1::Element::S_OUT, 1, v1::Element::UNIFORM)),
      "elements[1].channel:", {"output channel", "got UNIFORM"}));
}

TEST(GenomeProtoTest, RejectsOutputWithoutChannel) {
  EXPECT_TRUE(
      IsError(ErrorAtIndexOne(OneElement(v1::Element::S_OUT, -1,
                                         v1::Element::CHANNEL_NONE)),
              "elements[1].channel:", {"output channel", "got CHANNEL_NONE"}));
}

TEST(GenomeProtoTest, RejectsRegionOrFactorWithChannel) {
  const v1::Element::Type types[] = {v1::Element::P, v1::Element::G_INTERNAL,
                                     v1::Element::G_MORPHOGEN};
  for (v1::Element::Type type : types) {
    const std::string what =
        "a " + v1::Element::Type_Name(type) + " element has no channel";
    EXPECT_TRUE(
        IsError(ErrorAtIndexOne(OneElement(type, 1, v1::Element::MATERNAL_1)),
                "elements[1].channel:", {what, "got MATERNAL_1"}));
  }
}

TEST(GenomeProtoTest, RejectsUnspecifiedType) {
  EXPECT_TRUE(IsError(ErrorAtIndexOne(OneElement(v1::Element::TYPE_UNSPECIFIED,
                                                 1, v1::Element::CHANNEL_NONE)),
                      "elements[1].type:", {"got 0"}));
}

TEST(GenomeProtoTest, RejectsUnknownEnumNumbers) {
  // Proto3 enums are open: a binary message may carry numbers the schema
  // does not name.
  v1::Genome message = OneElement(v1::Element::P, 1, v1::Element::CHANNEL_NONE);
  message.mutable_elements(0)->set_type(static_cast<v1::Element::Type>(17));
  EXPECT_TRUE(IsError(ErrorAtIndexOne(message), "elements[1].type:", {"17"}));

  message = OneElement(v1::Element::S_OUT, 1, v1::Element::CHANNEL_NONE);
  message.mutable_elements(0)->set_channel(
      static_cast<v1::Element::Channel>(12));
  EXPECT_TRUE(
      IsError(ErrorAtIndexOne(message), "elements[1].channel:", {"got 12"}));
}

TEST(GenomeProtoTest, AcceptsGenomeAtTheSizeLimit) {
  EXPECT_TRUE(GenomeFromProto(PElements(1000)).ok());
  const Result<Genome> genome =
      GenomeFromProto(PElements(static_cast<int>(kMaxGenomeElements)));
  ASSERT_TRUE(genome.ok()) << genome.status().ToString();
  EXPECT_EQ(genome->elements.size(), kMaxGenomeElements);
}

TEST(GenomeProtoTest, RejectsGenomeOverTheSizeLimit) {
  const Result<Genome> genome =
      GenomeFromProto(PElements(static_cast<int>(kMaxGenomeElements) + 1));
  ASSERT_FALSE(genome.ok());
  EXPECT_TRUE(IsError(genome.status(), "elements:",
                      {std::to_string(kMaxGenomeElements + 1) + " elements",
                       "limit of " + std::to_string(kMaxGenomeElements)}));
}

// ValidateGenome on hand-built genomes (the checks GenomeFromProto cannot
// reach through the proto's types).
Genome ValidGenome() {
  Genome genome;
  genome.elements = {{ElementType::kP, 1, 1.0, 1.0, -1},
                     {ElementType::kGInternal, -1, 2.0, 2.0, -1},
                     {ElementType::kSIn, 1, 3.0, 3.0, 0},
                     {ElementType::kSOut, -1, 4.0, 4.0, 5}};
  return genome;
}

TEST(ValidateGenomeTest, AcceptsValidGenome) {
  EXPECT_TRUE(ValidateGenome(ValidGenome()).ok());
}

TEST(ValidateGenomeTest, NamesElementAndFieldOfBadSign) {
  Genome genome = ValidGenome();
  genome.elements[2].sign = -2;
  EXPECT_EQ(ValidateGenome(genome).message(),
            "elements[2].sign: must be +1 or -1, got -2");
}

TEST(ValidateGenomeTest, NamesElementOfNonFiniteCoordinate) {
  testing::FpTrapsOff traps_off;
  Genome genome = ValidGenome();
  genome.elements[3].y = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(IsError(ValidateGenome(genome), "elements[3]", {"finite"}));
}

// CHEMICAL (docs/model.md §10.2) is proto channel 11, after the outputs,
// and input channel 4; an output element cannot have it.
TEST(GenomeProtoTest, ChemicalInputRoundTrips) {
  v1::Genome message;
  v1::Element* e = message.add_elements();
  e->set_type(v1::Element::S_IN);
  e->set_sign(1);
  e->set_x(1.5);
  e->set_channel(v1::Element::CHEMICAL);
  Result<Genome> genome = GenomeFromProto(message);
  ASSERT_TRUE(genome.ok()) << genome.status().ToString();
  EXPECT_EQ(genome->elements[0].channel,
            static_cast<int>(InputChannel::kChemical));
  EXPECT_EQ(GenomeToProto(*genome).SerializeAsString(),
            message.SerializeAsString());
  e->set_type(v1::Element::S_OUT);
  EXPECT_FALSE(GenomeFromProto(message).ok());
}

TEST(ValidateGenomeTest, RejectsChannelOutOfRange) {
  Genome genome = ValidGenome();
  genome.elements[2].channel = kInputChannels;
  EXPECT_TRUE(IsError(ValidateGenome(genome), "elements[2].channel:"));
  genome = ValidGenome();
  genome.elements[2].channel = -1;
  EXPECT_TRUE(IsError(ValidateGenome(genome), "elements[2].channel:"));
  genome = ValidGenome();
  genome.elements[3].channel = kOutputChannels;
  EXPECT_TRUE(IsError(ValidateGenome(genome), "elements[3].channel:"));
  genome = ValidGenome();
  genome.elements[1].channel = 0;
  EXPECT_TRUE(IsError(ValidateGenome(genome), "elements[1].channel:"));
}

TEST(ValidateGenomeTest, RejectsUnknownType) {
  Genome genome = ValidGenome();
  genome.elements[0].type = static_cast<ElementType>(9);
  EXPECT_TRUE(IsError(ValidateGenome(genome), "elements[0].type:"));
}

TEST(ValidateGenomeTest, RejectsTooManyElements) {
  Genome genome;
  genome.elements.resize(kMaxGenomeElements);
  EXPECT_TRUE(ValidateGenome(genome).ok());
  genome.elements.emplace_back();
  EXPECT_TRUE(IsError(ValidateGenome(genome), "elements:"));
}

TEST(GenomeNamesTest, NameEveryTypeAndChannel) {
  EXPECT_STREQ(ElementTypeName(ElementType::kP), "P");
  EXPECT_STREQ(ElementTypeName(ElementType::kGInternal), "G_INTERNAL");
  EXPECT_STREQ(ElementTypeName(ElementType::kGMorphogen), "G_MORPHOGEN");
  EXPECT_STREQ(ElementTypeName(ElementType::kSIn), "S_IN");
  EXPECT_STREQ(ElementTypeName(ElementType::kSOut), "S_OUT");
  // The names match the proto's enum names.
  EXPECT_STREQ(InputChannelName(static_cast<int>(InputChannel::kChemical)),
               "CHEMICAL");
  EXPECT_EQ(v1::Element::Channel_Name(v1::Element::CHEMICAL), "CHEMICAL");
  for (int c = 0; c < kPaperInputChannels; ++c) {
    EXPECT_EQ(InputChannelName(c),
              v1::Element::Channel_Name(static_cast<v1::Element::Channel>(
                  v1::Element::MATERNAL_0 + c)));
  }
  for (int c = 0; c < kOutputChannels; ++c) {
    EXPECT_EQ(OutputChannelName(c),
              v1::Element::Channel_Name(
                  static_cast<v1::Element::Channel>(v1::Element::DIVIDE + c)));
  }
  EXPECT_STREQ(InputChannelName(-1), "?");
  EXPECT_STREQ(InputChannelName(kInputChannels), "?");
  EXPECT_STREQ(OutputChannelName(kOutputChannels), "?");
}

}  // namespace
}  // namespace animat
