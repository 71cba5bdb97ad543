// Every parameter of a run configuration declared once: each table names
// its message's fields, every field of the configuration messages has a
// row (so a proto field added without one fails here), every enum value
// converts both ways, and `animat config defaults`' commented text reads
// back as the defaults.
#include <google/protobuf/descriptor.h>

#include <map>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "common/io/param_table.h"
#include "common/io/proto_file.h"
#include "master/evolution/evolution_params.h"

namespace animat {
namespace {

using google::protobuf::Descriptor;
using google::protobuf::FieldDescriptor;

// "model.physics.mass", ...: every scalar field under `d`.
void CollectFields(const Descriptor& d, const std::string& prefix,
                   std::set<std::string>* names) {
  for (int i = 0; i < d.field_count(); ++i) {
    const FieldDescriptor& f = *d.field(i);
    const std::string name = prefix + std::string(f.name());
    if (f.cpp_type() == FieldDescriptor::CPPTYPE_MESSAGE) {
      CollectFields(*f.message_type(), name + ".", names);
    } else {
      names->insert(name);
    }
  }
}

TEST(ParamTablesTest, EveryTableNamesItsMessagesFields) {
  const Status status = CheckRunParamTables();
  EXPECT_TRUE(status.ok()) << status.ToString();
}

TEST(ParamTablesTest, EveryFieldOfARunConfigurationHasOneRow) {
  std::set<std::string> fields;
  CollectFields(*v1::RunConfig::descriptor(), "", &fields);
  // Model v2's switch, read into contact_rule and never written.
  fields.erase("model.physics.contacts");
  std::set<std::string> rows;
  for (const ParamDoc& doc : RunParamDocs()) {
    EXPECT_TRUE(rows.insert(doc.name).second) << "two rows: " << doc.name;
    EXPECT_FALSE(doc.doc.empty()) << doc.name;
  }
  EXPECT_EQ(rows, fields);
}

TEST(ParamTablesTest, EveryEnumValueConvertsBothWays) {
  const Descriptor& physics = *v1::PhysicsConfig::descriptor();
  for (const char* field : {"integrator", "drag_update", "contact_rule"}) {
    const auto* e = physics.FindFieldByName(field)->enum_type();
    for (int i = 1; i < e->value_count(); ++i) {
      v1::PhysicsConfig m;
      m.GetReflection()->SetEnumValue(&m, physics.FindFieldByName(field),
                                      e->value(i)->number());
      PhysicsParams p;
      ASSERT_TRUE(PhysicsParamsFromProto(m, &p).ok()) << e->value(i)->name();
      const v1::PhysicsConfig back = PhysicsParamsToProto(p);
      EXPECT_EQ(back.GetReflection()->GetEnumValue(
                    back, physics.FindFieldByName(field)),
                e->value(i)->number())
          << e->value(i)->name();
    }
  }
  for (auto precision : {v1::GrnConfig::DOUBLE, v1::GrnConfig::FLOAT}) {
    v1::GrnConfig m;
    m.set_precision(precision);
    GrnParams p;
    ASSERT_TRUE(GrnParamsFromProto(m, &p).ok());
    EXPECT_EQ(GrnParamsToProto(p).precision(), precision);
  }
}

TEST(ParamTablesTest, UnspecifiedKeepsTheDefaultAndUnknownIsNamed) {
  v1::PhysicsConfig m;
  m.set_integrator(v1::PhysicsConfig::INTEGRATOR_UNSPECIFIED);
  PhysicsParams p;
  ASSERT_TRUE(PhysicsParamsFromProto(m, &p).ok());
  EXPECT_EQ(p.integrator, PhysicsParams().integrator);
  m.set_integrator(static_cast<v1::PhysicsConfig::Integrator>(9));
  EXPECT_EQ(PhysicsParamsFromProto(m, &p).message(),
            "physics.integrator: unknown value 9");
  v1::EvaluationConfig e;
  e.set_fitness(static_cast<v1::EvaluationConfig::Fitness>(7));
  v1::Config config;
  *config.mutable_evaluation() = e;
  ModelConfig model;
  EXPECT_EQ(ConfigFromProto(config, &model).message(),
            "evaluation.fitness: unknown value 7");
}

TEST(ParamTablesTest, TheCommentedDefaultsReadBackAsTheDefaults) {
  const std::string text = AnnotateText(
      SerializeProto(RunSettingsToProto(RunSettings{}), ProtoFormat::kText),
      RunParamDocs());
  EXPECT_NE(text.find("  physics {\n    # the mass of every cell; > 0\n"
                      "    mass: 1\n"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("    # the longest delay (steps); [0, 127]\n"),
            std::string::npos);
  EXPECT_NE(text.find("    # what selection maximises; one of DISTANCE, "
                      "DISTANCE_WITHIN_ENERGY_BUDGET\n"),
            std::string::npos);
  EXPECT_NE(text.find("  # the run's random streams\n  seed: 1\n"),
            std::string::npos);
  v1::RunConfig back;
  ASSERT_TRUE(ParseProto(text, ProtoFormat::kText, &back).ok());
  EXPECT_EQ(
      SerializeProto(back, ProtoFormat::kText),
      SerializeProto(RunSettingsToProto(RunSettings{}), ProtoFormat::kText));
}

TEST(ParamTablesTest, RangesAreDescribedAsTheyAreChecked) {
  std::map<std::string, std::string> values;
  for (const ParamDoc& doc : RunParamDocs()) values[doc.name] = doc.values;
  EXPECT_EQ(values["model.grn.dt"], "(0, 1]");
  EXPECT_EQ(values["model.physics.actuation_max"], "[0, 0.5)");
  EXPECT_EQ(values["model.physics.substeps"], "[1, 1024]");
  EXPECT_EQ(values["model.physics.mass"], "> 0");
  EXPECT_EQ(values["model.guidance.enabled"], "");
  EXPECT_EQ(values["evolution.mutation.coordinate_sigma"], "[0, 1e+06]");
  EXPECT_EQ(values["model.physics.contact_rule"], "one of NONE, UNJOINED, ALL");
}

}  // namespace
}  // namespace animat
