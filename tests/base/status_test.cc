#include "common/base/status.h"

#include <memory>
#include <string>
#include <utility>

#include <gtest/gtest.h>

namespace animat {
namespace {

TEST(StatusTest, DefaultIsOk) {
  const Status status;
  EXPECT_TRUE(status.ok());
  EXPECT_EQ(status.code(), StatusCode::kOk);
  EXPECT_EQ(status.message(), "");
  EXPECT_EQ(status.ToString(), "OK");
  EXPECT_TRUE(Status::Ok().ok());
}

TEST(StatusTest, FactoriesSetCodeAndMessage) {
  const struct {
    Status status;
    StatusCode code;
    const char* text;
  } cases[] = {
      {Status::InvalidArgument("bad"), StatusCode::kInvalidArgument,
       "invalid argument: bad"},
      {Status::NotFound("gone"), StatusCode::kNotFound, "not found: gone"},
      {Status::IoError("disk"), StatusCode::kIoError, "I/O error: disk"},
      {Status::Internal("bug"), StatusCode::kInternal, "internal error: bug"},
  };
  for (const auto& c : cases) {
    EXPECT_FALSE(c.status.ok()) << c.text;
    EXPECT_EQ(c.status.code(), c.code) << c.text;
    EXPECT_EQ(c.status.ToString(), c.text);
  }
  EXPECT_EQ(Status::NotFound("gone").message(), "gone");
}

TEST(StatusTest, WithPrefixPrependsToErrors) {
  const Status status = Status::InvalidArgument("sign: must be +1 or -1")
                            .WithPrefix("elements[3]")
                            .WithPrefix("genome.json");
  EXPECT_EQ(status.code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(status.message(),
            "genome.json: elements[3]: sign: must be +1 or -1");
}

TEST(StatusTest, WithPrefixLeavesOkAlone) {
  const Status status = Status::Ok().WithPrefix("genome.json");
  EXPECT_TRUE(status.ok());
  EXPECT_EQ(status.message(), "");
}

TEST(ResultTest, HoldsValue) {
  Result<std::string> result = std::string("animat");
  ASSERT_TRUE(result.ok());
  EXPECT_TRUE(result.status().ok());
  EXPECT_EQ(result.value(), "animat");
  EXPECT_EQ(*result, "animat");
  EXPECT_EQ(result->size(), 6u);
  result->append("s");
  EXPECT_EQ(*result, "animats");
}

TEST(ResultTest, MovesOutMoveOnlyValue) {
  Result<std::unique_ptr<int>> result = std::make_unique<int>(7);
  ASSERT_TRUE(result.ok());
  const std::unique_ptr<int> value = std::move(result).value();
  ASSERT_NE(value, nullptr);
  EXPECT_EQ(*value, 7);
}

TEST(ResultTest, HoldsError) {
  const Result<int> result = Status::NotFound("genome.json: no such file");
  EXPECT_FALSE(result.ok());
  EXPECT_EQ(result.status().code(), StatusCode::kNotFound);
  EXPECT_EQ(result.status().message(), "genome.json: no such file");
}

TEST(ResultDeathTest, BuiltFromOkIsAnInternalError) {
  // A broken precondition: asserts in debug builds, and in release builds
  // the Result still carries an error rather than a missing value.
  EXPECT_DEBUG_DEATH(
      {
        const Result<int> result = Status::Ok();
        EXPECT_FALSE(result.ok());
        EXPECT_EQ(result.status().code(), StatusCode::kInternal);
      },
      "needs an error");
}

}  // namespace
}  // namespace animat
