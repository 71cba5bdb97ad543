#include "figures/snapshot_strip.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <set>
#include <string>
#include <vector>

#include "tests/analysis/synthetic_swimmer.h"
#include "tests/svg/xml.h"

namespace animat::figures {
namespace {

struct Swim {
  analysis::Recording recording;
  analysis::Analysis analysis;
};

StripOptions Strip(int snapshots, std::optional<int64_t> start = {}) {
  StripOptions options;
  options.snapshots = snapshots;
  options.start_step = start;
  return options;
}

Swim AnalyseTrace(const v1::Trace& trace) {
  Swim s;
  Result<analysis::Recording> r = analysis::RecordingFromTrace(trace);
  EXPECT_TRUE(r.ok()) << r.status().ToString();
  if (!r.ok()) return s;
  s.recording = std::move(r).value();
  Result<analysis::Analysis> a = analysis::Analyze(s.recording, {});
  EXPECT_TRUE(a.ok()) << a.status().ToString();
  if (a.ok()) s.analysis = std::move(a).value();
  return s;
}

Swim Analyse(const testing::SyntheticSwimmer& swimmer) {
  return AnalyseTrace(swimmer.Trace());
}

double Number(const testing::XmlElement* element, const std::string& key) {
  return std::atof(element->Attribute(key).c_str());
}

TEST(SnapshotStripTest, ShowsOneCycleInEvenSteps) {
  const Swim s = Analyse(testing::SyntheticSwimmer{});  // Period 80.
  Result<std::vector<int>> frames =
      CycleFrames(s.recording, s.analysis, Strip(6));
  ASSERT_TRUE(frames.ok()) << frames.status().ToString();
  // One frame per step from step 0, so frame k is step k: from step 2000,
  // 80 / 6 = 13.3 steps apart, then the cycle's end.
  EXPECT_EQ(*frames,
            (std::vector<int>{2000, 2013, 2027, 2040, 2053, 2067, 2080}));
}

TEST(SnapshotStripTest, HasOneSnapshotPerFrameWithEveryCellAndSpring) {
  const Swim s = Analyse(testing::SyntheticSwimmer{});
  Result<std::string> svg = SnapshotStripSvg(s.recording, s.analysis, Strip(6));
  ASSERT_TRUE(svg.ok()) << svg.status().ToString();
  testing::XmlReader reader;
  std::optional<testing::XmlElement> root = reader.Parse(*svg);
  ASSERT_TRUE(root.has_value()) << reader.error();
  const auto snapshots = root->FindAll("g", "snapshot");
  ASSERT_EQ(snapshots.size(), 6u);
  const char* steps[] = {"2000", "2013", "2027", "2040", "2053", "2067"};
  for (size_t j = 0; j < snapshots.size(); ++j) {
    EXPECT_EQ(snapshots[j]->Attribute("data-step"), steps[j]);
    EXPECT_EQ(snapshots[j]->FindAll("circle", "cell").size(), 8u);
    EXPECT_EQ(snapshots[j]->FindAll("line", "spring").size(), 10u);
  }
  EXPECT_EQ(root->FindAll("g", "distance").size(), 1u);
  EXPECT_EQ(snapshots.back()->FindAll("g", "distance").size(), 1u);
}

TEST(SnapshotStripTest, ColoursCellsByWhatTheyDoToTheirSprings) {
  // Every cell in phase: e − c = 0.3 cos(2π step / 80). At step 2000 it
  // peaks (its rate, 0.3 (1 − cos(2π/80)) ≈ 9e-4 per step, is below the
  // neutral rate); a sixth of a period later it falls, and two thirds
  // later it rises.
  const Swim s = Analyse(testing::SyntheticSwimmer{});
  Result<std::string> svg = SnapshotStripSvg(s.recording, s.analysis, Strip(6));
  ASSERT_TRUE(svg.ok());
  testing::XmlReader reader;
  std::optional<testing::XmlElement> root = reader.Parse(*svg);
  ASSERT_TRUE(root.has_value());
  const auto snapshots = root->FindAll("g", "snapshot");
  ASSERT_EQ(snapshots.size(), 6u);
  auto colours = [&](int j) {
    std::set<std::string> fills;
    for (const testing::XmlElement* c :
         snapshots[j]->FindAll("circle", "cell")) {
      fills.insert(c->Attribute("fill"));
    }
    return fills;
  };
  EXPECT_EQ(colours(0), std::set<std::string>{"#2ca02c"});  // Neutral.
  EXPECT_EQ(colours(1), std::set<std::string>{"#1f77b4"});  // Contracting.
  EXPECT_EQ(colours(4), std::set<std::string>{"#d62728"});  // Expanding.
}

// Cells are discs of their own radius, all at the strip's one scale, and
// fit in their panels.
TEST(SnapshotStripTest, DrawsCellsAsDiscsOfTheirRadius) {
  testing::SyntheticSwimmer swimmer;
  v1::Trace trace = swimmer.Trace();
  std::vector<double> radii;
  for (int i = 0; i < swimmer.cells(); ++i) {
    radii.push_back(0.6 + 0.15 * i);  // 0.6 to 1.65 radii.
    trace.mutable_body()->mutable_nodes(i)->set_radius(radii.back());
  }
  const Swim s = AnalyseTrace(trace);
  Result<std::string> svg = SnapshotStripSvg(s.recording, s.analysis, Strip(6));
  ASSERT_TRUE(svg.ok()) << svg.status().ToString();
  testing::XmlReader reader;
  std::optional<testing::XmlElement> root = reader.Parse(*svg);
  ASSERT_TRUE(root.has_value()) << reader.error();
  const auto snapshots = root->FindAll("g", "snapshot");
  ASSERT_EQ(snapshots.size(), 6u);
  for (const testing::XmlElement* snapshot : snapshots) {
    SCOPED_TRACE(snapshot->Attribute("data-step"));
    const auto cells = snapshot->FindAll("circle", "cell");
    ASSERT_EQ(cells.size(), 8u);
    // The scale: pixels between cells 0 and 7 over radii between them
    // (frame k is motion step k).
    const int k = std::atoi(snapshot->Attribute("data-step").c_str());
    const double world = Length(s.recording.at(k, 7) - s.recording.at(k, 0));
    const double pixels =
        std::hypot(Number(cells[7], "cx") - Number(cells[0], "cx"),
                   Number(cells[7], "cy") - Number(cells[0], "cy"));
    const double scale = pixels / world;
    const auto panels = snapshot->FindAll("rect");
    ASSERT_EQ(panels.size(), 1u);
    const double left = Number(panels[0], "x");
    const double top = Number(panels[0], "y");
    for (int i = 0; i < 8; ++i) {
      const double r = Number(cells[i], "r");
      EXPECT_NEAR(r, radii[i] * scale, 0.02) << "cell " << i;
      EXPECT_GE(Number(cells[i], "cx") - r, left) << "cell " << i;
      EXPECT_LE(Number(cells[i], "cx") + r, left + Number(panels[0], "width"))
          << "cell " << i;
      EXPECT_GE(Number(cells[i], "cy") - r, top) << "cell " << i;
      EXPECT_LE(Number(cells[i], "cy") + r, top + Number(panels[0], "height"))
          << "cell " << i;
    }
  }
}

TEST(SnapshotStripTest, NeedsAPeriodAndACycleThatFits) {
  testing::SyntheticSwimmer still;
  still.amplitude.assign(8, 0.0);
  const Swim no_period = Analyse(still);
  Result<std::string> none =
      SnapshotStripSvg(no_period.recording, no_period.analysis, {});
  ASSERT_FALSE(none.ok());
  // Which window, and that no other would do: nothing actuates.
  EXPECT_EQ(none.status().message(),
            "the actuation has no dominant period in motion steps 2000 to 4000 "
            "(the second half of the motion); no cell actuates anywhere in the "
            "motion (no e − c changes by more than 0.0002 per step), so there "
            "is no cycle to show");

  const Swim s = Analyse(testing::SyntheticSwimmer{});
  Result<std::string> late =
      SnapshotStripSvg(s.recording, s.analysis, Strip(6, 3950));
  ASSERT_FALSE(late.ok());
  EXPECT_NE(late.status().message().find(
                "window: motion steps 2000 to 4000 (the second half of the "
                "motion); --start, --from and --to choose another"),
            std::string::npos)
      << late.status().message();
  EXPECT_TRUE(SnapshotStripSvg(s.recording, s.analysis, Strip(6, 3900)).ok());
  EXPECT_FALSE(SnapshotStripSvg(s.recording, s.analysis, Strip(0)).ok());
  EXPECT_FALSE(SnapshotStripSvg(s.recording, s.analysis, Strip(81)).ok());
}

// An animat that stops actuating before the second half of its motion has
// its cycle shown where it actuates; in a window asked for without
// actuation, the error says where the actuation is.
TEST(SnapshotStripTest, AnAnimatThatStopsActuatingShowsACycleWhereItActuates) {
  testing::SyntheticSwimmer stops;
  stops.still_after = 1000;
  const Swim s = Analyse(stops);
  EXPECT_EQ(s.analysis.from_step, 0);
  Result<std::string> svg = SnapshotStripSvg(s.recording, s.analysis, {});
  ASSERT_TRUE(svg.ok()) << svg.status().ToString();

  Result<analysis::Analysis> asked = analysis::Analyze(
      s.recording, {.from_step = 2000, .to_step = std::nullopt});
  ASSERT_TRUE(asked.ok()) << asked.status().ToString();
  Result<std::string> none = SnapshotStripSvg(s.recording, *asked, {});
  ASSERT_FALSE(none.ok());
  EXPECT_EQ(none.status().message(),
            "the actuation has no dominant period in motion steps 2000 to 4000 "
            "(as asked); no cell actuates in it: the animat actuates in motion "
            "steps 0 to 1000 (--from 0 --to 1000), so there is no cycle to "
            "show; --from and --to choose another window");
}

}  // namespace
}  // namespace animat::figures
