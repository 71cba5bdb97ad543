#include "figures/analysis_plots.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <numbers>

#include "tests/analysis/synthetic_swimmer.h"
#include "tests/svg/xml.h"

namespace animat::figures {
namespace {

struct Swim {
  analysis::Recording recording;
  analysis::Analysis analysis;
};

Swim Analyse(const testing::SyntheticSwimmer& swimmer) {
  Swim s;
  Result<analysis::Recording> r = analysis::RecordingFromTrace(swimmer.Trace());
  EXPECT_TRUE(r.ok()) << r.status().ToString();
  if (!r.ok()) return s;
  s.recording = std::move(r).value();
  Result<analysis::Analysis> a = analysis::Analyze(s.recording, {});
  EXPECT_TRUE(a.ok()) << a.status().ToString();
  if (a.ok()) s.analysis = std::move(a).value();
  return s;
}

testing::XmlElement Parse(const std::string& svg) {
  testing::XmlReader reader;
  std::optional<testing::XmlElement> root = reader.Parse(svg);
  EXPECT_TRUE(root.has_value()) << reader.error();
  return root.value_or(testing::XmlElement{});
}

// The number of points of a polyline.
size_t Points(const testing::XmlElement& polyline) {
  const std::string p = polyline.Attribute("points");
  return static_cast<size_t>(std::count(p.begin(), p.end(), ','));
}

TEST(AnalysisPlotsTest, TheDefaultRangeIsSomeCyclesFromTheWindowStart) {
  const Swim s = Analyse(testing::SyntheticSwimmer{});
  const StepRange four = DefaultStepRange(s.analysis, 4);
  EXPECT_EQ(four.from, 2000);
  EXPECT_EQ(four.to, 2320);
  const StepRange all = DefaultStepRange(s.analysis, 0);
  EXPECT_EQ(all.to, 4000);
  EXPECT_EQ(DefaultStepRange(s.analysis, 1000).to, 4000);
}

TEST(AnalysisPlotsTest, ActivityHasTwoAxesWithTwoSidesEach) {
  const Swim s = Analyse(testing::SyntheticSwimmer{});
  const testing::XmlElement root = Parse(
      LinePlotSvg(ActivityPlot(s.analysis, DefaultStepRange(s.analysis, 4))));
  const auto panels = root.FindAll("g", "panel");
  ASSERT_EQ(panels.size(), 2u);
  for (const testing::XmlElement* panel : panels) {
    const auto series = panel->FindAll("polyline", "series");
    ASSERT_EQ(series.size(), 2u);
    EXPECT_EQ(Points(*series[0]), 321u);  // Steps 2000 to 2320.
  }
  EXPECT_EQ(
      panels[0]->FindAll("polyline", "series")[0]->Attribute("data-label"),
      "front");
  EXPECT_EQ(
      panels[1]->FindAll("polyline", "series")[1]->Attribute("data-label"),
      "right");
}

TEST(AnalysisPlotsTest, ActivityOfABodyWithoutSidesLeavesThemOut) {
  testing::SyntheticSwimmer line;
  line.rows = 1;
  const Swim s = Analyse(line);
  const testing::XmlElement root = Parse(
      LinePlotSvg(ActivityPlot(s.analysis, DefaultStepRange(s.analysis, 2))));
  const auto panels = root.FindAll("g", "panel");
  ASSERT_EQ(panels.size(), 2u);
  EXPECT_EQ(panels[0]->FindAll("polyline", "series").size(), 2u);
  EXPECT_EQ(panels[1]->FindAll("polyline", "series").size(), 0u);
  // The empty panel says why it is empty; the other says nothing.
  EXPECT_TRUE(panels[0]->FindAll("text", "empty").empty());
  const auto note = panels[1]->FindAll("text", "empty");
  ASSERT_EQ(note.size(), 1u);
  EXPECT_EQ(note[0]->text,
            "no cell is on the left or on the right: every cell lies on the "
            "front–back axis");

  // A cell of the chain is on that axis, not on a side.
  Result<LinePlot> cells =
      CellsPlot(s.recording, s.analysis, {1}, DefaultStepRange(s.analysis, 2));
  ASSERT_TRUE(cells.ok()) << cells.status().ToString();
  EXPECT_EQ(
      cells->panels[0].title.rfind("cell 1 (back, on the front–back axis", 0),
      0u)
      << cells->panels[0].title;
}

TEST(AnalysisPlotsTest, CellsHaveOnePanelEachWithExpansionAndContraction) {
  const Swim s = Analyse(testing::SyntheticSwimmer{});
  Result<LinePlot> plot = CellsPlot(s.recording, s.analysis, {1, 6, 7},
                                    DefaultStepRange(s.analysis, 2));
  ASSERT_TRUE(plot.ok()) << plot.status().ToString();
  const testing::XmlElement root = Parse(LinePlotSvg(*plot));
  const auto panels = root.FindAll("g", "panel");
  ASSERT_EQ(panels.size(), 3u);
  for (const testing::XmlElement* panel : panels) {
    const auto series = panel->FindAll("polyline", "series");
    ASSERT_EQ(series.size(), 2u);
    EXPECT_EQ(series[0]->Attribute("data-label"), "expansion e");
    EXPECT_EQ(series[0]->Attribute("stroke"), "#d62728");
    EXPECT_EQ(series[1]->Attribute("data-label"), "contraction c");
    EXPECT_EQ(Points(*series[1]), 161u);  // Steps 2000 to 2160.
  }
  EXPECT_EQ(plot->panels[0].title.rfind("cell 1 (back, right", 0), 0u);
  EXPECT_EQ(plot->panels[1].title.rfind("cell 6 (front, left", 0), 0u);
  EXPECT_FALSE(CellsPlot(s.recording, s.analysis, {8}, {2000, 2100}).ok());
  EXPECT_FALSE(CellsPlot(s.recording, s.analysis, {1}, {5000, 5100}).ok());
}

TEST(AnalysisPlotsTest, DefaultCellsAreTheDriversFirst) {
  testing::SyntheticSwimmer swimmer;
  swimmer.amplitude.assign(8, 0.1);
  swimmer.amplitude[6] = 0.5;
  const Swim s = Analyse(swimmer);
  ASSERT_FALSE(s.analysis.drivers.empty());
  EXPECT_EQ(DefaultCells(s.analysis, 2).front(), 6);
  EXPECT_EQ(DefaultCells(s.analysis, 2).size(), 2u);
  EXPECT_EQ(DefaultCells(s.analysis, 20).size(), 8u);
}

TEST(AnalysisPlotsTest, FitnessHasBestMeanAndMedianPerRun) {
  FitnessCurves a{"seed 1",        "radii swum",    {0, 1, 2},
                  {0.5, 0.7, 0.9}, {0.1, 0.2, 0.3}, {0.05, 0.1, 0.2}};
  FitnessCurves b{"seed 2",   "radii swum", {0, 1},
                  {0.4, 0.8}, {0.2, 0.3},   {std::nullopt, 0.25}};
  const testing::XmlElement root = Parse(LinePlotSvg(FitnessPlot({a, b})));
  ASSERT_EQ(root.FindAll("g", "panel").size(), 1u);
  const auto series = root.FindAll("polyline", "series");
  ASSERT_EQ(series.size(), 6u);
  EXPECT_EQ(series[0]->Attribute("data-label"), "seed 1 best");
  EXPECT_EQ(series[4]->Attribute("data-label"), "seed 2 mean");
  EXPECT_EQ(Points(*series[0]), 3u);
  EXPECT_EQ(Points(*series[5]), 1u);  // The missing median is left out.
  EXPECT_NE(series[0]->Attribute("stroke"), series[3]->Attribute("stroke"));
  EXPECT_EQ(series[1]->Attribute("stroke-dasharray"), "6,3");
  EXPECT_EQ(FitnessPlot({a, b}).panels[0].y_label, "fitness (radii swum)");
}

TEST(AnalysisPlotsTest, FitnessAxisNamesUnitsOnlyWhenRunsShareThem) {
  FitnessCurves a{"seed 1", "radii swum", {0}, {0.5}, {0.1}, {0.05}};
  FitnessCurves b{
      "seed 2", "radii closer to the source, mean", {0}, {0.4}, {0.2}, {0.1}};
  EXPECT_EQ(FitnessPlot({b}).panels[0].y_label,
            "fitness (radii closer to the source, mean)");
  EXPECT_EQ(FitnessPlot({a, b}).panels[0].y_label, "fitness");
  a.units.clear();
  EXPECT_EQ(FitnessPlot({a}).panels[0].y_label, "fitness");
}

}  // namespace
}  // namespace animat::figures
