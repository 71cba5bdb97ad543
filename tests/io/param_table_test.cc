// Parameters declared once (common/io/param_table.h): rows read, written
// and checked through reflection, and a table that names a field wrongly
// is caught.
#include "common/io/param_table.h"

#include <gtest/gtest.h>

#include "animat/v1/config.pb.h"
#include "common/physics/physics_params.h"

namespace animat {
namespace {

// A struct of two parameters against the physics message's fields.
struct Two {
  double mass = 1.0;
  int substeps = 2;
};

constexpr ParamRow<Two> kTwo[] = {
    {"mass", &Two::mass, ParamRange::Positive(), "of every cell"},
    {"substeps", &Two::substeps, ParamRange::Closed(1, 8), "per step"},
};

TEST(ParamTableTest, ReadsOnlyWhatIsPresentAndWritesEveryRow) {
  v1::PhysicsConfig m;
  Two two;
  ReadParams<Two>(m, kTwo, &two);
  EXPECT_EQ(two.mass, 1.0);  // Absent: the default stays.
  EXPECT_EQ(two.substeps, 2);
  m.set_substeps(5);
  ReadParams<Two>(m, kTwo, &two);
  EXPECT_EQ(two.mass, 1.0);
  EXPECT_EQ(two.substeps, 5);
  two.mass = 0.25;
  v1::PhysicsConfig out;
  WriteParams<Two>(two, kTwo, &out);
  EXPECT_TRUE(out.has_mass());
  EXPECT_EQ(out.mass(), 0.25);
  EXPECT_EQ(out.substeps(), 5);
  EXPECT_FALSE(out.has_dt());  // No row, not written.
}

TEST(ParamTableTest, ChecksNameTheFieldAsValidateDoes) {
  Two two;
  EXPECT_TRUE(CheckParams<Two>("physics", two, kTwo).ok());
  two.mass = -1.0;
  two.substeps = 9;
  EXPECT_EQ(CheckParams<Two>("physics", two, kTwo).message(),
            RequirePositive("physics.mass", -1.0).message());
  two.mass = 1.0;
  EXPECT_EQ(CheckParams<Two>("physics", two, kTwo).message(),
            RequireIntInRange("physics.substeps", 9, 1, 8).message());
  two.substeps = 8;
  EXPECT_TRUE(CheckParams<Two>("physics", two, kTwo).ok());
}

TEST(ParamTableTest, ATableNamingNoFieldOrTheWrongTypeIsCaught) {
  const v1::PhysicsConfig m;
  EXPECT_TRUE(CheckParamTable<Two>(m, kTwo).ok());
  constexpr ParamRow<Two> kMissing[] = {
      {"masss", &Two::mass, ParamRange::Positive(), "a typo"}};
  EXPECT_NE(CheckParamTable<Two>(m, kMissing).message().find("masss"),
            std::string::npos);
  constexpr ParamRow<Two> kWrongType[] = {
      {"mass", &Two::substeps, ParamRange::Closed(1, 8), "an int"}};
  EXPECT_FALSE(CheckParamTable<Two>(m, kWrongType).ok());
  // An enum is no numeric field.
  constexpr ParamRow<Two> kEnum[] = {
      {"integrator", &Two::substeps, ParamRange::Closed(1, 8), "an enum"}};
  EXPECT_FALSE(CheckParamTable<Two>(m, kEnum).ok());
}

// The physics table names its message's fields, and every one of its
// parameters goes through the conversions and back unchanged.
TEST(ParamTableTest, ThePhysicsTableIsItsMessages) {
  const Status status =
      CheckParamTable<PhysicsParams>(v1::PhysicsConfig(), PhysicsParamTable());
  EXPECT_TRUE(status.ok()) << status.ToString();
  EXPECT_EQ(PhysicsParamTable().size(), 15u);
  PhysicsParams p;
  p.contact_stiffness = 123.5;
  p.substeps = 7;
  PhysicsParams back;
  ASSERT_TRUE(PhysicsParamsFromProto(PhysicsParamsToProto(p), &back).ok());
  EXPECT_EQ(back.contact_stiffness, 123.5);
  EXPECT_EQ(back.substeps, 7);
}

}  // namespace
}  // namespace animat
