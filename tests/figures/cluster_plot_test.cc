#include "figures/cluster_plot.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "tests/svg/xml.h"

namespace animat::figures {
namespace {

using analysis::ClusteredAnimat;
using analysis::StrategyClustering;
using analysis::StrategyLabel;

testing::XmlElement Parse(const std::string& svg) {
  testing::XmlReader reader;
  std::optional<testing::XmlElement> root = reader.Parse(svg);
  EXPECT_TRUE(root.has_value()) << reader.error();
  return root.value_or(testing::XmlElement{});
}

// One animat of each label, along the first component.
StrategyClustering Clustering() {
  StrategyClustering c;
  c.clusters = 2;
  c.projection.explained = {0.6, 0.3};
  int i = 0;
  for (StrategyLabel label :
       {StrategyLabel::kTurtle, StrategyLabel::kShark, StrategyLabel::kWorm,
        StrategyLabel::kJellyfish, StrategyLabel::kOther}) {
    ClusteredAnimat a;
    a.name = std::string(analysis::StrategyName(label)) + " & co";
    a.label = label;
    a.cluster = i % 2;
    a.position = {static_cast<double>(i), 0.5 * i};
    c.animats.push_back(a);
    ++i;
  }
  return c;
}

TEST(ClusterPlotTest, DrawsEachAnimatWithItsLabelsShapeAndClustersColour) {
  const testing::XmlElement root =
      Parse(ClusterPlotSvg(Clustering(), "clusters"));
  EXPECT_EQ(root.FindAll("title")[0]->text, "clusters");
  const auto animats = root.FindAll("g", "animat");
  ASSERT_EQ(animats.size(), 5u);
  const char* shapes[] = {"polygon", "polygon", "polygon", "circle", "circle"};
  const char* labels[] = {"turtle", "shark", "worm", "jellyfish", "other"};
  std::string colours[2];
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(animats[i]->Attribute("data-label"), labels[i]);
    EXPECT_EQ(animats[i]->Attribute("data-cluster"), std::to_string(i % 2));
    EXPECT_EQ(animats[i]->Attribute("data-name"),
              std::string(labels[i]) + " & co");
    ASSERT_EQ(animats[i]->FindAll(shapes[i], "marker").size(), 1u) << i;
    EXPECT_EQ(animats[i]->FindAll("text", "number")[0]->text,
              std::to_string(i + 1));
    EXPECT_EQ(root.FindAll("text", "key")[i]->text,
              std::to_string(i + 1) + "  " + labels[i] + " & co");
    // Other is a ring in its cluster's colour; the rest are filled with it.
    const testing::XmlElement* marker =
        animats[i]->FindAll(shapes[i], "marker")[0];
    const std::string colour =
        i == 4 ? marker->Attribute("stroke") : marker->Attribute("fill");
    if (colours[i % 2].empty()) colours[i % 2] = colour;
    EXPECT_EQ(colour, colours[i % 2]) << i;
  }
  EXPECT_NE(colours[0], colours[1]);
  EXPECT_EQ(root.FindAll("g", "legend").size(), 1u);
}

TEST(ClusterPlotTest, TheFirstComponentRunsRightAndTheSecondUp) {
  const testing::XmlElement root =
      Parse(ClusterPlotSvg(Clustering(), "clusters"));
  const auto jelly = root.FindAll("g", "animat")[3]->FindAll("circle")[0];
  const auto ring = root.FindAll("g", "animat")[4]->FindAll("circle")[0];
  EXPECT_GT(std::atof(ring->Attribute("cx").c_str()),
            std::atof(jelly->Attribute("cx").c_str()));
  EXPECT_LT(std::atof(ring->Attribute("cy").c_str()),
            std::atof(jelly->Attribute("cy").c_str()));
  // The axes say how much of the variance each component holds.
  bool first = false;
  for (const testing::XmlElement* text : root.FindAll("text")) {
    first =
        first || text->text.find("(60% of the variance)") != std::string::npos;
  }
  EXPECT_TRUE(first);
}

}  // namespace
}  // namespace animat::figures
