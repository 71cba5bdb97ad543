#include "figures/line_plot.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tests/svg/xml.h"
#include "tests/test_util.h"

namespace animat::figures {
namespace {

testing::XmlElement Parse(const std::string& svg) {
  testing::XmlReader reader;
  std::optional<testing::XmlElement> root = reader.Parse(svg);
  EXPECT_TRUE(root.has_value()) << reader.error();
  return root.value_or(testing::XmlElement{});
}

Series Line(const std::string& label, std::vector<double> y) {
  Series s{label, "#000000", "", {}, std::move(y)};
  for (size_t i = 0; i < s.y.size(); ++i) s.x.push_back(i);
  return s;
}

TEST(LinePlotTest, DrawsEveryPanelAndSeries) {
  LinePlot plot;
  plot.title = "two panels";
  plot.x_label = "step";
  plot.panels = {
      Panel{"first", "y", {Line("a", {1, 2, 3}), Line("b", {3, 2, 1})}, {}, {}},
      Panel{"second", "y", {Line("c", {0, -1, 5})}, {}, {}}};
  const testing::XmlElement root = Parse(LinePlotSvg(plot));
  EXPECT_EQ(root.name, "svg");
  const auto panels = root.FindAll("g", "panel");
  ASSERT_EQ(panels.size(), 2u);
  ASSERT_EQ(panels[0]->FindAll("polyline", "series").size(), 2u);
  ASSERT_EQ(panels[1]->FindAll("polyline", "series").size(), 1u);
  EXPECT_EQ(
      panels[0]->FindAll("polyline", "series")[1]->Attribute("data-label"),
      "b");
  EXPECT_EQ(root.FindAll("title")[0]->text, "two panels");
}

TEST(LinePlotTest, PointsMapIntoThePlotArea) {
  LinePlot plot;
  plot.width = 400;
  plot.panel_height = 100;
  plot.panels = {Panel{"", "", {Line("a", {0, 10})}, 0.0, 10.0}};
  const testing::XmlElement root = Parse(LinePlotSvg(plot));
  // x 0..1 spans the plot area [70, 400 − 150]; y 0..10 spans [156, 56].
  EXPECT_EQ(root.FindAll("polyline", "series")[0]->Attribute("points"),
            "70,156 250,56");
}

TEST(LinePlotTest, TheYAxisEndsOnAWholeTick) {
  LinePlot plot;
  plot.width = 400;
  plot.panel_height = 100;
  plot.panels = {Panel{"", "", {Line("a", {0, 1.318})}, {}, {}}};
  const testing::XmlElement root = Parse(LinePlotSvg(plot));
  // Ticks 0, 0.5, 1, so the axis runs to 1.5: 1.318 is 87.9% up.
  EXPECT_EQ(root.FindAll("polyline", "series")[0]->Attribute("points"),
            "70,156 250,68.13");
}

TEST(LinePlotTest, LeavesOutPointsAndSeriesThatAreNotFinite) {
  testing::FpTrapsOff traps_off;  // NaN is made on purpose.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  LinePlot plot;
  plot.panels = {Panel{
      "", "", {Line("gap", {1, nan, 3}), Line("none", {nan, nan})}, {}, {}}};
  const testing::XmlElement root = Parse(LinePlotSvg(plot));
  const auto series = root.FindAll("polyline", "series");
  ASSERT_EQ(series.size(), 1u);
  const std::string points = series[0]->Attribute("points");
  EXPECT_EQ(std::count(points.begin(), points.end(), ','), 2) << points;
}

TEST(LinePlotTest, AChartWithoutDataStillHasAxes) {
  LinePlot plot;
  plot.panels = {Panel{"empty", "y", {}, {}, {}}};
  const testing::XmlElement root = Parse(LinePlotSvg(plot));
  EXPECT_EQ(root.FindAll("g", "panel").size(), 1u);
  EXPECT_TRUE(root.FindAll("polyline", "series").empty());
  EXPECT_GE(root.FindAll("line").size(), 2u);
}

TEST(LinePlotTest, AnEmptyPanelSaysSo) {
  LinePlot plot;
  Panel explained{"sides", "y", {Line("nan", {NAN})}, {}, {}};
  explained.empty_note = "no cell is on the left or on the right";
  plot.panels = {Panel{"data", "y", {Line("a", {1, 2})}, {}, {}},
                 Panel{"nothing", "y", {}, {}, {}}, explained};
  const testing::XmlElement root = Parse(LinePlotSvg(plot));
  const auto panels = root.FindAll("g", "panel");
  ASSERT_EQ(panels.size(), 3u);
  EXPECT_TRUE(panels[0]->FindAll("text", "empty").empty());
  ASSERT_EQ(panels[1]->FindAll("text", "empty").size(), 1u);
  EXPECT_EQ(panels[1]->FindAll("text", "empty")[0]->text, "no data");
  ASSERT_EQ(panels[2]->FindAll("text", "empty").size(), 1u);
  EXPECT_EQ(panels[2]->FindAll("text", "empty")[0]->text,
            "no cell is on the left or on the right");
}

TEST(LinePlotTest, TicksAreRoundNumbersCoveringTheRange) {
  EXPECT_EQ(Ticks(0, 1, 5), (std::vector<double>{0, 0.2, 0.4, 0.6, 0.8, 1}));
  EXPECT_EQ(Ticks(3, 97, 5), (std::vector<double>{20, 40, 60, 80}));
  EXPECT_EQ(Ticks(3, 97, 4), (std::vector<double>{50}));
  EXPECT_EQ(Ticks(-0.03, 0.03, 3), (std::vector<double>{-0.02, 0, 0.02}));
  EXPECT_EQ(Ticks(2, 2, 5), (std::vector<double>{2}));
}

}  // namespace
}  // namespace animat::figures
