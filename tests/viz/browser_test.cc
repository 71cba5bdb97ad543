// The page of `animat render` in headless Chromium: the real binary, a
// real (short) simulation, the real browser. Skipped, saying so, only when
// Chromium is not installed (scripts/setup.sh installs it; CI runs this).
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "animat/v1/trace.pb.h"
#include "common/io/proto_file.h"
#include "tests/test_util.h"
#include "tests/viz/trace_builder.h"
#include "viz/actuation.h"

namespace animat {
namespace {

namespace fs = std::filesystem;

struct Outcome {
  int exit_code = -1;
  std::string output;  // Standard output only.
};

Outcome Shell(const std::string& command) {
  Outcome run;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return run;
  char buffer[4096];
  size_t n;
  while ((n = fread(buffer, 1, sizeof(buffer), pipe)) > 0) {
    run.output.append(buffer, n);
  }
  const int status = pclose(pipe);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

// $ANIMAT_CHROMIUM, else chromium or chromium-browser on the PATH.
std::optional<std::string> FindChromium() {
  if (const char* chosen = std::getenv("ANIMAT_CHROMIUM")) return chosen;
  const char* path = std::getenv("PATH");
  if (path == nullptr) return std::nullopt;
  for (const char* name : {"chromium", "chromium-browser"}) {
    std::string dirs = path;
    size_t start = 0;
    while (start <= dirs.size()) {
      const size_t end = std::min(dirs.find(':', start), dirs.size());
      const fs::path candidate =
          fs::path(dirs.substr(start, end - start)) / name;
      if (access(candidate.c_str(), X_OK) == 0) return candidate.string();
      start = end + 1;
    }
  }
  return std::nullopt;
}

// What the page shows of one frame, read from its DOM.
struct Shown {
  std::string frame, phase, step, text;  // #step's data attributes, text.
  std::string playing;                   // body's data-playing.
  // Each circle of #cells: its colour class, its radius (text), and the
  // indices of those also of class "overlap".
  std::vector<std::string> cells;
  std::vector<std::string> radii;
  std::vector<int> overlapping;
  std::string drawn;  // The picture's data-cells: "discs" or "dots".
};

// The value of attribute `name` in the start tag `tag`, or "".
std::string Attribute(const std::string& tag, const std::string& name) {
  const std::string key = " " + name + "=\"";
  const size_t at = tag.find(key);
  if (at == std::string::npos) return "";
  const size_t start = at + key.size();
  return tag.substr(start, tag.find('"', start) - start);
}

// The start tag beginning with `prefix`, or "".
std::string StartTag(const std::string& dom, const std::string& prefix,
                     size_t from = 0) {
  const size_t at = dom.find(prefix, from);
  if (at == std::string::npos) return "";
  return dom.substr(at, dom.find('>', at) + 1 - at);
}

Shown Read(const std::string& dom) {
  Shown shown;
  const std::string step = StartTag(dom, "<output id=\"step\"");
  shown.frame = Attribute(step, "data-frame");
  shown.phase = Attribute(step, "data-phase");
  shown.step = Attribute(step, "data-step");
  const size_t text = dom.find(step) + step.size();
  shown.text = dom.substr(text, dom.find("</output>", text) - text);
  shown.playing = Attribute(StartTag(dom, "<body"), "data-playing");
  shown.drawn = Attribute(StartTag(dom, "<svg id=\"view\""), "data-cells");
  const size_t cells = dom.find("<g id=\"cells\">");
  const size_t end = dom.find("</g>", cells);
  for (size_t at = dom.find("<circle", cells); at < end;
       at = dom.find("<circle", at + 1)) {
    const std::string tag = StartTag(dom, "<circle", at);
    std::string classes = Attribute(tag, "class");
    const std::string overlap = " overlap";
    if (classes.size() > overlap.size() && classes.ends_with(overlap)) {
      shown.overlapping.push_back(static_cast<int>(shown.cells.size()));
      classes.resize(classes.size() - overlap.size());
    }
    shown.cells.push_back(classes);
    shown.radii.push_back(Attribute(tag, "r"));
  }
  return shown;
}

class BrowserTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::optional<std::string> chromium = FindChromium();
    if (!chromium) {
      GTEST_SKIP() << "Chromium is not installed (scripts/setup.sh installs "
                      "it; ANIMAT_CHROMIUM names another binary)";
    }
    chromium_ = *chromium;
    const ::testing::TestInfo* test =
        ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::path(::testing::TempDir()) /
           ("animat-browser-" + std::string(test->name()) + "-" +
            std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);

    // A short evaluation: 400 development, 40 equilibration and 200 motion
    // steps, every 20th recorded.
    const std::string config = (dir_ / "short.txtpb").string();
    ASSERT_TRUE(WriteFile(config,
                          "evaluation { equilibration_steps: 40 "
                          "motion_steps: 200 }\n")
                    .ok());
    const std::string animat = std::string(ANIMAT_BIN_DIR) + "/animat";
    const std::string trace = (dir_ / "trace.binpb").string();
    page_ = (dir_ / "page.html").string();
    const Outcome simulated =
        Shell(animat + " simulate --genome " +
              testing::TestData("genomes/seed-1198.json") + " --config " +
              config + " --every 20 --trace " + trace + " 2>&1");
    ASSERT_EQ(simulated.exit_code, 0) << simulated.output;
    const Outcome rendered =
        Shell(animat + " render --trace " + trace + " -o " + page_ + " 2>&1");
    ASSERT_EQ(rendered.exit_code, 0) << rendered.output;
    ASSERT_TRUE(ReadProtoFile(trace, &trace_).ok());
    ASSERT_EQ(trace_.result().status(), v1::EvaluationResult::OK);
    ASSERT_EQ(trace_.development_size(), 21);  // 0, 20, ..., 380, 399.
    ASSERT_EQ(trace_.frames_size(), 3 + 11);   // By 20 to 40, then to 200.
  }

  void TearDown() override {
    if (!dir_.empty()) fs::remove_all(dir_);
  }

  std::string Chromium(const std::string& action, const std::string& fragment,
                       int budget_ms = 0) {
    const std::string profile = (dir_ / "profile").string();
    std::string command =
        "timeout 120 " + chromium_ +
        " --headless --no-sandbox --disable-gpu --disable-quic"
        " --no-first-run --disable-background-networking"
        " --disable-component-update --disable-sync --hide-scrollbars"
        " --user-data-dir=" +
        profile + " " + action;
    if (budget_ms > 0) {
      command += " --virtual-time-budget=" + std::to_string(budget_ms);
    }
    return command + " 'file://" + page_ + "#" + fragment + "' 2>/dev/null";
  }

  // Opens the page at `fragment` and returns its DOM after `budget_ms` of
  // virtual time; with `png`, also a screenshot of it (its bytes).
  Shown Open(const std::string& fragment, int budget_ms,
             std::string* png = nullptr) {
    const std::string file = (dir_ / "shot.png").string();
    fs::remove(file);
    const std::string shoot =
        png != nullptr ? " --window-size=1000,700 --screenshot=" + file : "";
    const Outcome run =
        Shell(Chromium("--dump-dom" + shoot, fragment, budget_ms));
    EXPECT_EQ(run.exit_code, 0);
    EXPECT_NE(run.output.find("</html>"), std::string::npos) << run.output;
    if (png != nullptr) {
      Result<std::string> bytes = ReadFile(file);
      EXPECT_TRUE(bytes.ok()) << bytes.status().message();
      *png = bytes.ok() ? *bytes : "";
    }
    return Read(run.output);
  }

  int Frames() const {
    return trace_.development_size() + trace_.frames_size();
  }
  // The phase and step of page frame k: development, then the rest.
  std::pair<std::string, int> Expected(int k) const {
    if (k < trace_.development_size()) {
      return {"development", trace_.development(k).step()};
    }
    const v1::MotionFrame& f = trace_.frames(k - trace_.development_size());
    return {f.phase() == v1::MotionFrame::EQUILIBRATION ? "equilibration"
                                                        : "motion",
            f.step()};
  }
  // The colour classes the trace gives the body's nodes at page frame k.
  std::vector<std::string> ExpectedClasses(int k) const {
    const int m = k - trace_.development_size();
    const std::vector<viz::Actuation> actuation =
        viz::ClassifyActuation(m > 0 ? &trace_.frames(m - 1) : nullptr,
                               trace_.frames(m), viz::kDefaultNeutralRate);
    std::vector<std::string> classes;
    for (const viz::Actuation a : actuation) {
      classes.push_back(a == viz::Actuation::kExpanding     ? "expanding"
                        : a == viz::Actuation::kContracting ? "contracting"
                                                            : "neutral");
    }
    return classes;
  }

  std::string chromium_;
  fs::path dir_;
  std::string page_;
  v1::Trace trace_;
};

TEST_F(BrowserTest, EachFrameShowsItsPictureStepAndCellsFromTheTrace) {
  const int development = trace_.development_size();
  // The motion frame whose cells are the most varied, to check colours.
  int varied = development + 3;
  size_t kinds = 0;
  for (int k = development + 3; k < Frames(); ++k) {
    std::vector<std::string> classes = ExpectedClasses(k);
    std::sort(classes.begin(), classes.end());
    const size_t n =
        std::unique(classes.begin(), classes.end()) - classes.begin();
    if (n > kinds) varied = k, kinds = n;
  }
  ASSERT_GE(kinds, 2u) << "the test genome should expand and contract";

  std::vector<std::string> pictures;
  for (const int k : {5, development, varied, Frames() - 1}) {
    SCOPED_TRACE("frame " + std::to_string(k));
    pictures.emplace_back();
    const Shown shown =
        Open("frame=" + std::to_string(k), 500, &pictures.back());
    const auto [phase, step] = Expected(k);
    EXPECT_EQ(shown.frame, std::to_string(k));
    EXPECT_EQ(shown.phase, phase);
    EXPECT_EQ(shown.step, std::to_string(step));
    const std::string length = phase == "development" ? "399"
                               : phase == "motion"    ? "200"
                                                      : "40";
    EXPECT_EQ(shown.text,
              phase + " step " + std::to_string(step) + " / " + length);
    EXPECT_EQ(shown.playing, "false");
    if (phase == "development") {
      EXPECT_EQ(shown.cells,
                std::vector<std::string>(trace_.development(k).x_size(),
                                         "development"));
    } else {
      EXPECT_EQ(shown.cells, ExpectedClasses(k));
    }
    ASSERT_GT(pictures.back().size(), 1000u);
    EXPECT_EQ(pictures.back().substr(1, 3), "PNG");
  }
  // The same frame gives the same pixels, so different bytes mean a
  // different picture: every frame shown differs from the others.
  std::string again;
  Open("frame=" + std::to_string(varied), 500, &again);
  EXPECT_EQ(again, pictures[2]);
  for (size_t a = 0; a < pictures.size(); ++a) {
    for (size_t b = a + 1; b < pictures.size(); ++b) {
      EXPECT_NE(pictures[a], pictures[b]) << "pictures " << a << ", " << b;
    }
  }
}

// The text between the start tag beginning with `prefix` and the next '<'.
std::string TextAfter(const std::string& dom, const std::string& prefix) {
  const std::string tag = StartTag(dom, prefix);
  if (tag.empty()) return "";
  const size_t from = dom.find(tag) + tag.size();
  return dom.substr(from, dom.find('<', from) - from);
}

// The numbers of an attribute such as points="x,y x,y" or viewBox.
std::vector<double> Numbers(const std::string& text) {
  std::vector<double> numbers;
  std::string current;
  for (const char c : text + " ") {
    if (c == ',' || c == ' ') {
      if (!current.empty()) numbers.push_back(std::atof(current.c_str()));
      current.clear();
    } else {
      current += c;
    }
  }
  return numbers;
}

// A scale bar one grid square long, the model time of equilibration and
// motion frames, and the trace's file name without its folders.
TEST_F(BrowserTest, TheViewHasAScaleBarTheModelTimeAndTheFileName) {
  const std::string last = std::to_string(Frames() - 1);
  const Outcome run = Shell(
      Chromium("--window-size=1000,700 --dump-dom", "frame=" + last, 500));
  ASSERT_EQ(run.exit_code, 0);
  const std::string& dom = run.output;

  // The bar: as long as a grid square in the picture's own coordinates,
  // labelled with it, and as many screen pixels as the view's scale
  // gives (at most 1000 pixels across the view's width; data-pixels has
  // 4 significant digits).
  const std::string unit =
      Attribute(StartTag(dom, "<g id=\"grid\""), "data-unit");
  ASSERT_FALSE(unit.empty());
  const std::string scale = StartTag(dom, "<g id=\"scale\"");
  EXPECT_EQ(Attribute(scale, "data-radii"), unit);
  const std::vector<double> bar =
      Numbers(Attribute(StartTag(dom, "<polyline", dom.find(scale)), "points"));
  ASSERT_EQ(bar.size(), 8u);
  EXPECT_NEAR(bar[4] - bar[2], std::atof(unit.c_str()), 1e-9);
  EXPECT_EQ(TextAfter(dom.substr(dom.find(scale)), "<text"),
            unit + (unit == "1" ? " radius" : " radii"));
  const std::vector<double> view =
      Numbers(Attribute(StartTag(dom, "<svg id=\"view\""), "viewBox"));
  ASSERT_EQ(view.size(), 4u);
  const double pixels = std::atof(Attribute(scale, "data-pixels").c_str());
  EXPECT_GT(pixels, 10);
  EXPECT_LE(pixels, std::atof(unit.c_str()) * 1000 / view[2] * 1.001);

  // Model time: the step times physics.dt (0.05).
  const v1::MotionFrame& frame = trace_.frames(trace_.frames_size() - 1);
  ASSERT_EQ(frame.step(), 200);
  EXPECT_EQ(Attribute(StartTag(dom, "<span id=\"time\""), "data-time"), "10");
  EXPECT_EQ(TextAfter(dom, "<span id=\"time\""), "model time 10");

  // The file's name, not its path.
  EXPECT_EQ(TextAfter(dom, "<h1 id=\"title\""), "trace.binpb");

  // Development has no model time of the physics.
  const Outcome early =
      Shell(Chromium("--window-size=1000,700 --dump-dom", "frame=5", 500));
  EXPECT_EQ(Read(early.output).phase, "development");
  EXPECT_EQ(Attribute(StartTag(early.output, "<span id=\"time\""), "data-time"),
            "");
}

TEST_F(BrowserTest, PlayingAdvancesFramesAndTheCounterFollows) {
  const Shown shown = Open("frame=0&play&speed=0.5", 1000);
  const int frame = std::atoi(shown.frame.c_str());
  EXPECT_EQ(shown.playing, "true");
  ASSERT_GT(frame, 0);
  ASSERT_LT(frame, Frames());
  const auto [phase, step] = Expected(frame);
  EXPECT_EQ(shown.phase, phase);
  EXPECT_EQ(shown.step, std::to_string(step));
}

// With guidance (docs/model.md §10.2) the page draws every source, the
// recorded trial's filled, and the gradient's discs around it.
TEST_F(BrowserTest, GuidanceShowsTheSourcesAndTheGradient) {
  const std::string config = (dir_ / "guidance.txtpb").string();
  ASSERT_TRUE(WriteFile(config,
                        "evaluation { equilibration_steps: 40 "
                        "motion_steps: 200 }\nguidance { enabled: true }\n")
                  .ok());
  const std::string animat = std::string(ANIMAT_BIN_DIR) + "/animat";
  const std::string trace = (dir_ / "guidance.binpb").string();
  const Outcome simulated =
      Shell(animat + " simulate --genome " +
            testing::TestData("genomes/seed-1198.json") + " --config " +
            config + " --every 20 --trial 3 --trace " + trace + " 2>&1");
  ASSERT_EQ(simulated.exit_code, 0) << simulated.output;
  const Outcome rendered =
      Shell(animat + " render --trace " + trace + " -o " + page_ + " 2>&1");
  ASSERT_EQ(rendered.exit_code, 0) << rendered.output;
  const Outcome run =
      Shell(Chromium("--window-size=1000,700 --dump-dom", "frame=30", 500));
  ASSERT_EQ(run.exit_code, 0);
  const std::string& dom = run.output;
  auto circles = [&](const std::string& group) {
    std::vector<std::string> classes;
    const size_t begin = dom.find("<g id=\"" + group + "\">");
    EXPECT_NE(begin, std::string::npos) << group;
    const size_t end = dom.find("</g>", begin);
    for (size_t at = dom.find("<circle", begin); at < end;
         at = dom.find("<circle", at + 1)) {
      classes.push_back(Attribute(StartTag(dom, "<circle", at), "class"));
    }
    return classes;
  };
  EXPECT_EQ(circles("sources"),
            (std::vector<std::string>{"", "", "", "active"}));
  EXPECT_EQ(circles("gradient").size(), 3u);
  EXPECT_NE(dom.find("trial 3 (0 to 3)"), std::string::npos);
}

// Body nodes are discs of their radius; "discs" unticked (here by the
// fragment's &dots, which clicks it) brings back equal dots, smaller than
// any cell. Development snapshots are discs of their radius either way.
// (Radii that differ from cell to cell: the folding ring's test below.)
TEST_F(BrowserTest, CellsAreDiscsOfTheirRadiusAndTheToggleBringsBackDots) {
  const std::string last = std::to_string(Frames() - 1);
  const Shown discs = Open("frame=" + last, 500);
  EXPECT_EQ(discs.drawn, "discs");
  const int nodes = trace_.body().nodes_size();
  ASSERT_EQ(discs.radii.size(), static_cast<size_t>(nodes));
  double smallest = 1e9;
  for (int i = 0; i < nodes; ++i) {
    ASSERT_TRUE(trace_.body().nodes(i).has_radius()) << i;
    const double radius = trace_.body().nodes(i).radius();
    EXPECT_EQ(std::atof(discs.radii[i].c_str()), radius) << "node " << i;
    smallest = std::min(smallest, radius);
  }

  const Shown dots = Open("frame=" + last + "&dots", 500);
  EXPECT_EQ(dots.drawn, "dots");
  ASSERT_EQ(dots.radii.size(), static_cast<size_t>(nodes));
  for (int i = 0; i < nodes; ++i) {
    EXPECT_EQ(dots.radii[i], dots.radii[0]) << "node " << i;
  }
  EXPECT_GT(std::atof(dots.radii[0].c_str()), 0);
  EXPECT_LT(std::atof(dots.radii[0].c_str()), smallest);
  EXPECT_EQ(dots.cells, discs.cells);

  const Shown grown = Open("frame=5", 500);
  const Shown grown_dots = Open("frame=5&dots", 500);
  ASSERT_EQ(grown.radii.size(),
            static_cast<size_t>(trace_.development(5).radius_size()));
  for (int i = 0; i < trace_.development(5).radius_size(); ++i) {
    EXPECT_NEAR(std::atof(grown.radii[i].c_str()),
                trace_.development(5).radius(i), 5e-5);
  }
  EXPECT_EQ(grown_dots.radii, grown.radii);
}

// The hand-made folding ring (tests/viz/trace_builder.h): joined nodes 0
// and 1 overlap by 20% in every frame and are never marked; unjoined nodes
// 0 and 2 overlap by 7.3% in the folded frame, and are marked there only,
// with discs or dots. The heading gives the run's recorded deepest overlap,
// or says a trace from before it has none.
TEST_F(BrowserTest, OverlappingUnjoinedCellsAreMarkedJoinedOnesAreNot) {
  const std::string animat = std::string(ANIMAT_BIN_DIR) + "/animat";
  const std::string trace = (dir_ / "folding.binpb").string();
  auto render = [&](const v1::Trace& made) {
    ASSERT_TRUE(WriteProtoFile(trace, made).ok());
    const Outcome rendered =
        Shell(animat + " render --trace " + trace + " -o " + page_ + " 2>&1");
    ASSERT_EQ(rendered.exit_code, 0) << rendered.output;
  };
  ASSERT_NO_FATAL_FAILURE(render(testing::FoldingTrace()));
  struct Marks {
    Shown shown;
    std::string lines;  // data-cells of each line of #overlaps, joined.
    std::string overlap, overlap_cells, overlap_text;  // #overlap.
    std::string run, run_text;                         // #max-overlap.
  };
  auto open = [&](const std::string& fragment) {
    const Outcome run =
        Shell(Chromium("--window-size=1000,700 --dump-dom", fragment, 500));
    EXPECT_EQ(run.exit_code, 0);
    const std::string& dom = run.output;
    Marks marks;
    marks.shown = Read(dom);
    const size_t begin = dom.find("<g id=\"overlaps\">");
    EXPECT_NE(begin, std::string::npos);
    const size_t end = dom.find("</g>", begin);
    for (size_t at = dom.find("<line", begin); at < end;
         at = dom.find("<line", at + 1)) {
      marks.lines.push_back('[');
      marks.lines += Attribute(StartTag(dom, "<line", at), "data-cells");
      marks.lines.push_back(']');
    }
    const std::string overlap = StartTag(dom, "<span id=\"overlap\"");
    marks.overlap = Attribute(overlap, "data-overlap");
    marks.overlap_cells = Attribute(overlap, "data-cells");
    marks.overlap_text = TextAfter(dom, "<span id=\"overlap\"");
    marks.run =
        Attribute(StartTag(dom, "<span id=\"max-overlap\""), "data-overlap");
    marks.run_text = TextAfter(dom, "<span id=\"max-overlap\"");
    return marks;
  };

  const Marks open_ring = open("frame=1");
  EXPECT_EQ(open_ring.shown.phase, "motion");
  EXPECT_EQ(open_ring.shown.step, "0");
  EXPECT_EQ(open_ring.shown.radii,
            (std::vector<std::string>{"1", "0.5", "1", "0.5"}));
  EXPECT_EQ(open_ring.shown.overlapping, std::vector<int>{});
  EXPECT_EQ(open_ring.lines, "");
  EXPECT_EQ(open_ring.overlap, "0");
  EXPECT_EQ(open_ring.overlap_text, "no unjoined overlap");
  EXPECT_EQ(open_ring.run, "0.083");
  EXPECT_EQ(open_ring.run_text, "deepest unjoined overlap: 8.3%");

  for (const std::string fragment : {"frame=2", "frame=2&dots"}) {
    SCOPED_TRACE(fragment);
    const Marks folded = open(fragment);
    EXPECT_EQ(folded.shown.step, "10");
    EXPECT_EQ(folded.shown.drawn,
              fragment.ends_with("dots") ? "dots" : "discs");
    EXPECT_EQ(folded.shown.overlapping, (std::vector<int>{0, 2}));
    EXPECT_EQ(folded.shown.cells, std::vector<std::string>(4, "neutral"));
    EXPECT_EQ(folded.lines, "[0,2]");
    EXPECT_EQ(folded.overlap, "0.073");
    EXPECT_EQ(folded.overlap_cells, "0,2");
    EXPECT_EQ(folded.overlap_text, "unjoined overlap 7.3% (cells 0 and 2)");
    EXPECT_EQ(folded.run_text, "deepest unjoined overlap: 8.3%");
  }

  v1::Trace older = testing::FoldingTrace();
  older.mutable_result()->clear_max_overlap();
  ASSERT_NO_FATAL_FAILURE(render(older));
  const Marks unrecorded = open("frame=2");
  EXPECT_EQ(unrecorded.run, "");
  EXPECT_EQ(unrecorded.run_text, "deepest unjoined overlap: not recorded");
  EXPECT_EQ(unrecorded.overlap_text, "unjoined overlap 7.3% (cells 0 and 2)");
}

}  // namespace
}  // namespace animat
