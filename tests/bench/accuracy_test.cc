// The accuracy report's own logic: statistics, the Pareto front, the SVG
// writer, the candidate set and the animat set's kinds (bench/accuracy/).
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/accuracy/animat_set.h"
#include "bench/accuracy/candidates.h"
#include "bench/accuracy/experiment.h"
#include "bench/accuracy/report.h"
#include "bench/accuracy/stats.h"
#include "bench/accuracy/svg_plot.h"

namespace animat::accuracy {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(StatsTest, MedianOfOddCountIsTheMiddleValue) {
  EXPECT_EQ(Median({5, 1, 3}), 3);
}

TEST(StatsTest, MedianOfEvenCountIsTheMeanOfTheMiddleTwo) {
  EXPECT_EQ(Median({4, 1, 3, 2}), 2.5);
}

TEST(StatsTest, Percentile90InterpolatesBetweenRanks) {
  // Position 0.9 * 9 = 8.1 in 1..10: 9 + 0.1 * (10 - 9).
  EXPECT_DOUBLE_EQ(Percentile90({10, 9, 8, 7, 6, 5, 4, 3, 2, 1}), 9.1);
  // Position 0.9 * 10 = 9 exactly: the 10th value.
  EXPECT_EQ(Percentile90({0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10}), 9);
  EXPECT_EQ(Percentile90({7}), 7);
}

TEST(StatsTest, FailuresCountAsInfiniteErrors) {
  EXPECT_EQ(Median({1, 2, kInf}), 2);
  EXPECT_EQ(Median({1, 2, kInf, kInf}), kInf);
  EXPECT_EQ(Percentile90({1, 2, 3, kInf}), kInf);
  EXPECT_EQ(Percentile90({kInf, kInf}), kInf);
  // Ten finite values and one failure: the 90th percentile is still finite.
  EXPECT_EQ(Percentile90({0, 1, 2, 3, 4, 5, 6, 7, 8, 9, kInf}), 9);
}

TEST(StatsTest, QuantileOfNothingIsNaN) { EXPECT_TRUE(std::isnan(Median({}))); }

TEST(ParetoTest, KeepsOnlyUndominatedPointsInOrderOfCost) {
  const std::vector<CostError> points = {
      {4, 1},     // 0: front (most accurate).
      {2, 5},     // 1: front.
      {3, 5},     // 2: dominated by 1 (slower, same error).
      {1, 10},    // 3: front.
      {5, 2},     // 4: dominated by 0.
      {2, 6},     // 5: dominated by 1 (same cost, worse error).
      {0.5, 20},  // 6: front (fastest).
      {kInf, 0},  // 7: not usable.
      {3, kInf},  // 8: not usable.
  };
  EXPECT_EQ(ParetoFront(points), (std::vector<int>{6, 3, 1, 0}));
}

TEST(ParetoTest, EqualPointsAreAllOnTheFront) {
  const std::vector<CostError> points = {{1, 1}, {2, 2}, {1, 1}};
  EXPECT_EQ(ParetoFront(points), (std::vector<int>{0, 2}));
}

TEST(ParetoTest, EmptySetHasEmptyFront) {
  EXPECT_TRUE(ParetoFront({}).empty());
}

// Checks that `xml` is well-formed enough for any XML reader: tags nest and
// close, attribute values are quoted, '&' starts an entity, one root.
// Returns "" or what is wrong.
std::string CheckXml(const std::string& xml) {
  std::vector<std::string> open;
  int roots = 0;
  size_t i = 0;
  while (i < xml.size()) {
    if (xml[i] == '&') {
      bool entity = false;
      for (const char* e : {"&amp;", "&lt;", "&gt;", "&quot;", "&apos;"}) {
        entity = entity || xml.compare(i, std::string(e).size(), e) == 0;
      }
      if (!entity) return "bare & at " + std::to_string(i);
      ++i;
      continue;
    }
    if (xml[i] == '>') return "bare > at " + std::to_string(i);
    if (xml[i] != '<') {
      ++i;
      continue;
    }
    if (xml.compare(i, 2, "<?") == 0) {
      const size_t end = xml.find("?>", i);
      if (end == std::string::npos) return "unclosed <?";
      i = end + 2;
      continue;
    }
    // A tag: read to its '>' outside quotes.
    size_t j = i + 1;
    bool quoted = false;
    while (j < xml.size() && (quoted || xml[j] != '>')) {
      if (xml[j] == '"') quoted = !quoted;
      if (!quoted && xml[j] == '<')
        return "< inside a tag at " + std::to_string(j);
      ++j;
    }
    if (j >= xml.size()) return "unclosed tag at " + std::to_string(i);
    const std::string tag = xml.substr(i + 1, j - i - 1);
    i = j + 1;
    if (tag.empty()) return "empty tag";
    if (tag[0] == '/') {
      const std::string name = tag.substr(1);
      if (open.empty() || open.back() != name) {
        return "</" + name + "> does not close " +
               (open.empty() ? "anything" : "<" + open.back() + ">");
      }
      open.pop_back();
      continue;
    }
    const std::string name = tag.substr(0, tag.find_first_of(" \n/"));
    if (open.empty()) ++roots;
    if (tag.back() != '/') open.push_back(name);
  }
  if (!open.empty()) return "<" + open.back() + "> never closed";
  if (roots != 1) return std::to_string(roots) + " root elements";
  return "";
}

int Count(const std::string& text, const std::string& what) {
  int count = 0;
  for (size_t at = text.find(what); at != std::string::npos;
       at = text.find(what, at + 1)) {
    ++count;
  }
  return count;
}

TEST(XmlCheckTest, RejectsMalformedDocuments) {
  EXPECT_EQ(CheckXml("<a><b/></a>"), "");
  EXPECT_NE(CheckXml("<a><b></a>"), "");
  EXPECT_NE(CheckXml("<a>x & y</a>"), "");
  EXPECT_NE(CheckXml("<a/><b/>"), "");
}

TEST(SvgTest, WellFormedWithOnePointPerCandidateAndTheFrontDrawn) {
  const std::vector<PlotPoint> points = {
      {"E1", "semi-implicit Euler", 30, 0.05, true},
      {"E2", "semi-implicit Euler", 35, 0.04, false},
      {"R4", "RK4", 120, 1e-6, true},
      {"V2<&>'", "velocity Verlet", 60, 0.2, false},
      {"B1", "Bullet", 110, 0.05, false},
  };
  PlotOptions options;
  options.title = "speed & error";
  options.x_label = "ms";
  options.y_label = "error";
  options.legend_notes = {"a < b"};
  const std::string svg = PlotSvg(points, options);

  EXPECT_EQ(CheckXml(svg), "");
  EXPECT_EQ(svg.find("<?xml"), 0u);
  EXPECT_EQ(Count(svg, "<svg "), 1);
  EXPECT_EQ(Count(svg, "<circle class=\"point"), 5);
  EXPECT_EQ(Count(svg, "<circle class=\"point front\""), 2);
  // One circle per point plus one legend marker per group and the front's.
  EXPECT_EQ(Count(svg, "<circle "), 5 + 4 + 1);
  ASSERT_EQ(Count(svg, "<polyline class=\"front\""), 1);
  // The front's line runs through its two points.
  const size_t at = svg.find("<polyline class=\"front\"");
  const size_t from = svg.find("points=\"", at) + 8;
  const std::string coordinates = svg.substr(from, svg.find('"', from) - from);
  EXPECT_EQ(Count(coordinates, ","), 2) << coordinates;
  // Escaped as figures/ escape (common/svg), apostrophes too.
  EXPECT_NE(svg.find("V2&lt;&amp;&gt;&apos;"), std::string::npos);
  // Tick labels on both axes.
  EXPECT_NE(svg.find(">100<"), std::string::npos);
  EXPECT_NE(svg.find(">1e-6<"), std::string::npos);
}

TEST(SvgTest, LeavesOutPointsThatLogAxesCannotShow) {
  const std::vector<PlotPoint> points = {
      {"ok", "g", 10, 0.1, true},
      {"zero", "g", 20, 0, false},
      {"inf", "g", 30, kInf, false},
  };
  const std::string svg = PlotSvg(points, {});
  EXPECT_EQ(CheckXml(svg), "");
  EXPECT_EQ(Count(svg, "<circle class=\"point"), 1);
}

TEST(SvgTest, EmptyPlotIsStillWellFormed) {
  const std::string svg = PlotSvg({}, {});
  EXPECT_EQ(CheckXml(svg), "");
  EXPECT_EQ(Count(svg, "<circle class=\"point"), 0);
  EXPECT_EQ(Count(svg, "<polyline"), 0);
}

TEST(CandidatesTest, SetCoversEveryCombinationWithUniqueLabels) {
  const std::vector<Candidate> set = CandidateSet();
  // Euler, Verlet, RK4 x {1, 2, 4} x {explicit, stable} x {double, float};
  // Verlet x 3, explicit, x {double, float}; Verlet x 1 with 4 near
  // contacts and x 2 with 3 or 4, x {double, float}; Verlet with contacts
  // in inner sub-steps, (1, 4), (2, 2), (2, 3), (2, 4) x {double, float};
  // SSPRK3, Ralston's x {1, 2} x {double, float}; Bullet x {1, 2} x
  // {double, float}.
  EXPECT_EQ(set.size(), 3u * 3 * 2 * 2 + 2 + 3 * 2 + 4 * 2 + 2 * 2 * 2 + 4);
  std::set<std::string> labels;
  for (const Candidate& c : set) labels.insert(c.Label());
  EXPECT_EQ(labels.size(), set.size());
  EXPECT_EQ(ReferenceCandidate().Label(), "R16");
  EXPECT_EQ(DefaultCandidate().Label(), "V4f");
}

TEST(CandidatesTest, LabelsSelectCandidates) {
  Result<std::vector<Candidate>> some = SelectCandidates({"L1f", "R1f"});
  ASSERT_TRUE(some.ok()) << some.status().message();
  ASSERT_EQ(some->size(), 2u);
  EXPECT_EQ((*some)[0].Label(), "R1f");  // In the set's order.
  EXPECT_EQ((*some)[1].Label(), "L1f");
  Result<std::vector<Candidate>> all = SelectCandidates({});
  ASSERT_TRUE(all.ok());
  EXPECT_EQ(all->size(), CandidateSet().size());
  Result<std::vector<Candidate>> unknown = SelectCandidates({"R1f", "Q9"});
  ASSERT_FALSE(unknown.ok());
  EXPECT_NE(unknown.status().message().find("\"Q9\""), std::string::npos);
}

TEST(CandidatesTest, DefaultCandidateIsTheModelsDefaultConfig) {
  Result<ModelConfig> config = CandidateConfig(DefaultCandidate());
  ASSERT_TRUE(config.ok()) << config.status().message();
  const ModelConfig defaults;
  EXPECT_EQ(config->physics.integrator, defaults.physics.integrator);
  EXPECT_EQ(config->physics.substeps, defaults.physics.substeps);
  EXPECT_EQ(config->physics.contact_substeps,
            defaults.physics.contact_substeps);
  EXPECT_EQ(config->physics.drag_update, defaults.physics.drag_update);
  EXPECT_EQ(config->physics.backend, defaults.physics.backend);
  EXPECT_EQ(config->grn.precision, defaults.grn.precision);
}

// Regression: when the default precision became FLOAT, candidates that
// asked for DOUBLE by writing nothing ran in float.
TEST(CandidatesTest, EveryCandidateGetsThePrecisionItNames) {
  for (const Candidate& c : CandidateSet()) {
    Result<ModelConfig> config = CandidateConfig(c);
    ASSERT_TRUE(config.ok()) << c.Label() << ": " << config.status().message();
    EXPECT_EQ(config->grn.precision,
              c.precision == "FLOAT" ? Precision::kFloat : Precision::kDouble)
        << c.Label();
  }
}

TEST(CandidatesTest, ContactSubstepsAreWrittenAndLabelled) {
  Result<std::vector<Candidate>> some = SelectCandidates({"V2c4f", "V2f"});
  ASSERT_TRUE(some.ok()) << some.status().message();
  ASSERT_EQ(some->size(), 2u);
  for (const Candidate& c : *some) {
    Result<ModelConfig> config = CandidateConfig(c);
    ASSERT_TRUE(config.ok()) << c.Label() << ": " << config.status().message();
    EXPECT_EQ(config->physics.substeps, 2);
    // Written even when 0, so that a default with contact sub-steps does
    // not change the uniform candidates.
    EXPECT_EQ(config->physics.contact_substeps, c.Label() == "V2f" ? 0 : 4);
  }
  EXPECT_NE((*some)[1].Name().find("(×4 within n 0.1 of a contact)"),
            std::string::npos)
      << (*some)[1].Name();
  // Another n is written and read back.
  Candidate wider = (*some)[1];
  wider.contact_near = 0.25;
  Result<ModelConfig> config = CandidateConfig(wider);
  ASSERT_TRUE(config.ok()) << config.status().message();
  EXPECT_EQ(config->physics.contact_near, 0.25);
}

TEST(CandidatesTest, ContactInnerSubstepsAreWrittenAndLabelled) {
  Result<std::vector<Candidate>> some =
      SelectCandidates({"V1i4", "V2f", "V2i3f"});
  ASSERT_TRUE(some.ok()) << some.status().message();
  ASSERT_EQ(some->size(), 3u);
  const int expected[][2] = {{2, 0}, {1, 4}, {2, 3}};  // The set's order.
  for (size_t k = 0; k < some->size(); ++k) {
    const Candidate& c = (*some)[k];
    Result<ModelConfig> config = CandidateConfig(c);
    ASSERT_TRUE(config.ok()) << c.Label() << ": " << config.status().message();
    EXPECT_EQ(config->physics.substeps, expected[k][0]) << c.Label();
    EXPECT_EQ(config->physics.contact_inner_substeps, expected[k][1])
        << c.Label();
  }
  EXPECT_EQ((*some)[2].Name(),
            "verlet ×2 (contacts ×3 within each), explicit, float");
}

// Regression: the float-against-double table paired V2i3f with V2, a
// candidate without the inner contact sub-steps.
TEST(CandidatesTest, CounterpartDiffersInPrecisionOrBackendAlone) {
  const std::vector<Candidate> set = CandidateSet();
  const auto counterpart = [&set](const std::string& label) -> std::string {
    for (const Candidate& c : set) {
      if (c.Label() != label) continue;
      const int i = Counterpart(set, c);
      return i < 0 ? "none" : set[i].Label();
    }
    return "not in the set";
  };
  EXPECT_EQ(counterpart("V2f"), "V2");
  EXPECT_EQ(counterpart("V2i3f"), "V2i3");
  EXPECT_EQ(counterpart("V2c4f"), "V2c4");
  EXPECT_EQ(counterpart("R4sf"), "R4s");
  EXPECT_EQ(counterpart("B2f"), "E2f");  // Bullet: native, same precision.
  EXPECT_EQ(counterpart("B1"), "E1");
  // Double native candidates have none; nor has a float one whose double
  // is not in the set.
  EXPECT_EQ(counterpart("V2i3"), "none");
  const std::vector<Candidate> alone = {set[0]};
  for (const Candidate& c : set) {
    if (c.Label() == "V4f") {
      EXPECT_EQ(Counterpart(alone, c), -1);
    }
  }
}

TEST(CandidatesTest, ContactStiffnessIsWrittenOnlyWhenAsked) {
  Candidate c = DefaultCandidate();
  EXPECT_EQ(c.ConfigText().find("contact_stiffness"), std::string::npos);
  Result<ModelConfig> config = CandidateConfig(c);
  ASSERT_TRUE(config.ok()) << config.status().message();
  EXPECT_EQ(config->physics.contact_stiffness,
            PhysicsParams{}.contact_stiffness);
  // --contact-stiffness: every configuration at another k_c, the label
  // unchanged (a whole report runs at one k_c).
  c.contact_stiffness = 3000;
  config = CandidateConfig(c);
  ASSERT_TRUE(config.ok()) << config.status().message();
  EXPECT_EQ(config->physics.contact_stiffness, 3000);
  EXPECT_EQ(c.Label(), DefaultCandidate().Label());
}

TEST(CandidatesTest, ReferenceConfigIsRk4WithSixteenSubsteps) {
  Result<ModelConfig> config = CandidateConfig(ReferenceCandidate());
  ASSERT_TRUE(config.ok()) << config.status().message();
  EXPECT_EQ(config->physics.integrator, Integrator::kRk4);
  EXPECT_EQ(config->physics.substeps, 16);
  EXPECT_EQ(config->physics.drag_update, DragUpdate::kExplicit);
  EXPECT_EQ(config->physics.backend, PhysicsBackend::kNative);
  EXPECT_EQ(config->grn.precision, Precision::kDouble);
}

// The number of fields of each line of `csv` (quotes respected).
std::vector<int> FieldCounts(const std::string& csv) {
  std::vector<int> counts;
  int fields = 1;
  bool quoted = false;
  for (char c : csv) {
    if (c == '"') quoted = !quoted;
    if (quoted) continue;
    if (c == ',') ++fields;
    if (c == '\n') {
      counts.push_back(fields);
      fields = 1;
    }
  }
  return counts;
}

TEST(ReportTest, CsvFieldsWithCommasOrQuotesAreQuoted) {
  EXPECT_EQ(CsvField("plain"), "plain");
  EXPECT_EQ(CsvField("a, b"), "\"a, b\"");
  EXPECT_EQ(CsvField("say \"x\""), "\"say \"\"x\"\"\"");
}

TEST(ReportTest, WritersShowAnUnloadableCandidateAsARowWithItsError) {
  Report report;
  report.repeats = 1;
  report.animats = {"a"};
  report.reference_fitness = {1.0};
  CandidateResult broken;
  broken.candidate = CandidateSet().back();
  broken.error = "grn.precision: not supported";
  CandidateResult fine;
  fine.candidate = DefaultCandidate();
  fine.animats.push_back(
      {"a", "ok", "", 1.1, 1.0, 0.1, 0.2, 30.0, 29.0, 7, true});
  fine.fitness_error_median = fine.fitness_error_p90 = 0.1;
  fine.trajectory_error_median = fine.trajectory_error_p90 = 0.2;
  fine.ms_median = 30.0;
  fine.on_front = true;
  report.candidates = {fine, broken};

  const std::string md = SummaryMarkdown(report);
  EXPECT_NE(md.find("grn.precision: not supported"), std::string::npos);
  EXPECT_NE(md.find("| `V4f` |"), std::string::npos);
  EXPECT_NE(md.find("not run"), std::string::npos);
  const std::string csv = SummaryCsv(report);
  EXPECT_EQ(Count(csv, "\n"), 3);
  EXPECT_NE(csv.find("grn.precision: not supported"), std::string::npos);
  const std::vector<int> summary_fields = FieldCounts(csv);
  ASSERT_EQ(summary_fields.size(), 3u);
  EXPECT_EQ(summary_fields[1], summary_fields[0]);
  EXPECT_EQ(summary_fields[2], summary_fields[0]);
  const std::vector<int> accuracy_fields = FieldCounts(AccuracyCsv(report));
  ASSERT_EQ(accuracy_fields.size(), 3u);
  EXPECT_EQ(accuracy_fields[1], accuracy_fields[0]);
  EXPECT_EQ(accuracy_fields[2], accuracy_fields[0]);
  const std::string svg = ReportSvg(report);
  EXPECT_EQ(CheckXml(svg), "");
  EXPECT_EQ(Count(svg, "<circle class=\"point front\""), 1);
}

TEST(AnimatSetTest, EvolvedAnimatsAreTheFilesNamedEvolved) {
  EXPECT_TRUE(IsEvolvedName("evolved-s1-g098-76194"));
  EXPECT_FALSE(IsEvolvedName("seed-01198"));
  EXPECT_FALSE(IsEvolvedName("my-evolved-1"));
}

std::vector<std::string> Names(const std::vector<Animat>& animats) {
  std::vector<std::string> names;
  for (const Animat& a : animats) names.push_back(a.name);
  return names;
}

TEST(AnimatSetTest, QuickSubsetTakesTheFirstOfEachKindInOrder) {
  std::vector<Animat> set;
  for (const char* name : {"evolved-a", "evolved-b", "seed-1", "seed-2",
                           "seed-3", "seed-4", "seed-5"}) {
    set.push_back({name, Genome{}, IsEvolvedName(name), ""});
  }
  EXPECT_EQ(Names(QuickSubset(set, 4, 1)),
            (std::vector<std::string>{"evolved-a", "seed-1", "seed-2", "seed-3",
                                      "seed-4"}));
  // Fewer of a kind than asked: all of them.
  EXPECT_EQ(Names(QuickSubset(set, 1, 5)),
            (std::vector<std::string>{"evolved-a", "evolved-b", "seed-1"}));
  EXPECT_TRUE(QuickSubset(set, 0, 0).empty());
}

TEST(ReportTest, MixedSetGetsATableOfEachKindAndAKindColumn) {
  Report report;
  report.repeats = 1;
  report.animats = {"seed-1", "evolved-a"};
  report.evolved = {false, true};
  report.reference_fitness = {1.0, 50.0};
  CandidateResult c;
  c.candidate = DefaultCandidate();
  c.animats.push_back(
      {"seed-1", "ok", "", 1.1, 1.0, 0.1, 0.1, 20.0, 20.0, 7, true, false});
  c.animats.push_back({"evolved-a", "ok", "", 49.0, 50.0, 0.02, 0.03, 60.0,
                       60.0, 8, true, true});
  report.candidates = {c};

  const std::string md = SummaryMarkdown(report);
  EXPECT_NE(md.find("2 animats (1 random genomes, 1 evolved"),
            std::string::npos);
  EXPECT_NE(md.find("### Random and evolved animats"), std::string::npos);
  EXPECT_NE(md.find("| `V4f` | 1.0e-01 | 1.0e-01 | 20.0 | 2.0e-02 | 2.0e-02 | "
                    "60.0 |"),
            std::string::npos)
      << md;
  const std::string csv = AccuracyCsv(report);
  EXPECT_NE(csv.find(",seed-1,random,ok,"), std::string::npos);
  EXPECT_NE(csv.find(",evolved-a,evolved,ok,"), std::string::npos);

  // An all-random set has no such table.
  report.evolved = {false, false};
  report.candidates[0].animats[1].evolved = false;
  EXPECT_EQ(SummaryMarkdown(report).find("### Random and evolved"),
            std::string::npos);
}

CandidateResult Measured(const char* integrator, int substeps, double ms,
                         double p90, int swaps) {
  CandidateResult c;
  c.candidate.integrator = integrator;
  c.candidate.substeps = substeps;
  c.candidate.drag_update = "EXPLICIT";
  c.candidate.precision = "FLOAT";
  c.candidate.backend = "NATIVE";
  c.animats.push_back({"a", "ok", "", 1.0, 1.0, p90, p90, ms, ms, 7, true});
  c.fitness_error_median = c.fitness_error_p90 = p90;
  c.ms_median = ms;
  c.order_swaps = swaps;
  c.order_pairs = 10;
  return c;
}

TEST(RuleTest, CheapestCandidateWithinOnePercentAndNoSwapIsChosen) {
  std::vector<CandidateResult> set = {
      Measured("SEMI_IMPLICIT_EULER", 1, 17.0, 0.33, 20),  // Too coarse.
      Measured("VELOCITY_VERLET", 1, 19.0, 0.0101, 0),     // Just over 1%.
      Measured("VELOCITY_VERLET", 2, 25.0, 0.003, 1),      // Swaps a pair.
      Measured("RK4", 1, 28.0, 0.0002, 0),
      Measured("VELOCITY_VERLET", 4, 26.0, 0.01, 0),  // At 1%: meets.
  };
  EXPECT_FALSE(set[0].MeetsRule());
  EXPECT_FALSE(set[1].MeetsRule());
  EXPECT_FALSE(set[2].MeetsRule());
  EXPECT_TRUE(set[3].MeetsRule());
  EXPECT_TRUE(set[4].MeetsRule());
  EXPECT_EQ(RuleChoice(set), "V4f");
  // Within 5% of the cheapest counts as equally cheap: the more accurate
  // wins.
  set[3].ms_median = 27.3;
  EXPECT_EQ(RuleChoice(set), "R1f");
  set[3].ms_median = 28.0;
  // A failed evaluation disqualifies.
  set[4].failures = 1;
  EXPECT_EQ(RuleChoice(set), "R1f");
  set[3].error = "no effect";
  EXPECT_EQ(RuleChoice(set), "");

  Report report;
  report.repeats = 1;
  report.animats = {"a"};
  report.reference_fitness = {1.0};
  report.candidates = {set[0], Measured("RK4", 1, 27.0, 0.0002, 0)};
  report.rule_choice = RuleChoice(report.candidates);
  const std::string md = SummaryMarkdown(report);
  EXPECT_NE(md.find("**Chosen: `R1f`**"), std::string::npos) << md;
  EXPECT_NE(md.find("| **chosen** |"), std::string::npos);
}

TEST(RuleTest, TheDefaultMustHoldTheContactBound) {
  std::vector<CandidateResult> set = {
      Measured("VELOCITY_VERLET", 3, 20.0, 0.009, 0),
      Measured("VELOCITY_VERLET", 4, 26.0, 0.003, 0),
  };
  // Within the error clauses, one animat's cells overlap by 10.5%.
  set[0].max_overlap = 0.105;
  set[1].max_overlap = 0.082;
  EXPECT_FALSE(set[0].MeetsRule());
  EXPECT_TRUE(set[1].MeetsRule());
  EXPECT_EQ(RuleChoice(set), "V4f");
  // The bound is 10% / 1.2, inclusive.
  set[0].max_overlap = kRuleOverlap;
  EXPECT_TRUE(set[0].MeetsRule());
  EXPECT_EQ(RuleChoice(set), "V3f");
  set[0].max_overlap = std::nextafter(kRuleOverlap, 1.0);
  EXPECT_FALSE(set[0].MeetsRule());

  // Summarise takes the deepest over the ok evaluations only.
  CandidateResult c = Measured("VELOCITY_VERLET", 4, 26.0, 0.003, 0);
  c.animats.resize(2);
  c.animats[0].status = "ok";
  c.animats[0].max_overlap = 0.05;
  c.animats[1].status = "ok";
  c.animats[1].max_overlap = 0.07;
  Summarise(&c);
  EXPECT_EQ(c.max_overlap, 0.07);
  c.animats[1].status = "unstable";
  Summarise(&c);
  EXPECT_EQ(c.max_overlap, 0.05);
}

// A temporary folder with one genome (the test data's sample) and, when
// `model` is not empty, its model file.
std::string SetWithModelFile(const std::string& model) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(::testing::TempDir()) /
                       ("animat-set-" + std::to_string(model.size()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::copy_file(fs::path(ANIMAT_TEST_DATA_DIR) / "genomes" / "seed-1198.json",
                dir / "evolved-x.json");
  if (!model.empty()) {
    std::ofstream(dir / "evolved-x.model.txtpb") << model;
  }
  return dir.string();
}

TEST(AnimatSetTest, ModelFileGivesTheConstantsTheAnimatEvolvedUnder) {
  Result<std::vector<Animat>> set = LoadAnimatSet(
      SetWithModelFile("physics { drag_normal: 10 drag_tangential: 0.05 }"));
  ASSERT_TRUE(set.ok()) << set.status().message();
  ASSERT_EQ(set->size(), 1u);  // The model file is not a genome.
  ModelConfig rk4;
  rk4.physics.integrator = Integrator::kRk4;
  Result<ModelConfig> config = ForAnimat(rk4, set->front());
  ASSERT_TRUE(config.ok()) << config.status().message();
  EXPECT_EQ(config->physics.drag_normal, 10.0);
  EXPECT_EQ(config->physics.drag_tangential, 0.05);
  EXPECT_EQ(config->physics.integrator, Integrator::kRk4);  // Kept.
}

// An animat whose reference did not converge has no fitness to measure a
// candidate against: its error and its pairs are left out, its failures and
// times are not, and the summary names it with both fitnesses.
TEST(ConvergenceTest, UnconvergedAnimatsAreLeftOutOfErrorsAndSwaps) {
  CandidateResult c;
  c.candidate = DefaultCandidate();
  c.animats = {{"a", "ok", "", 1.0, 1.0, 0.001, 0.001, 10.0, 10.0, 1, true,
                false, 0.0, true},
               {"b", "ok", "", 2.5, 2.0, 0.25, 0.25, 30.0, 30.0, 2, true, false,
                0.0, false},
               {"c", "ok", "", 3.0, 3.0, 0.002, 0.002, 20.0, 20.0, 3, true,
                false, 0.0, true}};
  Summarise(&c);
  EXPECT_DOUBLE_EQ(c.fitness_error_median, 0.0015);  // Of a and c.
  EXPECT_LT(c.fitness_error_p90, 0.01);
  EXPECT_DOUBLE_EQ(c.ms_median, 20.0);  // Of all three.
  EXPECT_TRUE(c.MeetsRule());
  c.animats[1].status = "numerical_failure";
  Summarise(&c);
  EXPECT_EQ(c.failures, 1);  // A failure still disqualifies.

  // b swaps places with c against the reference, but b is left out.
  std::vector<accuracy::Run> reference(3), runs(3);
  const double ref[] = {1.0, 2.0, 3.0}, got[] = {1.0, 3.5, 3.0};
  for (int a = 0; a < 3; ++a) {
    reference[a].fitness = ref[a];
    runs[a].fitness = got[a];
  }
  int pairs = 0;
  EXPECT_EQ(OrderSwaps(runs, reference, {true, false, true}, &pairs), 0);
  EXPECT_EQ(pairs, 1);
  EXPECT_EQ(OrderSwaps(runs, reference, {true, true, true}, &pairs), 1);
  EXPECT_EQ(pairs, 3);

  Report report;
  report.repeats = 1;
  report.animats = {"a", "b", "c"};
  report.reference_fitness = {1.0, 2.0, 3.0};
  report.check_fitness = {1.0, 2.5, 3.0};
  report.converged = {true, false, true};
  report.candidates = {c};
  const std::string md = SummaryMarkdown(report);
  EXPECT_NE(md.find("2 of 3 animats"), std::string::npos) << md;
  EXPECT_NE(md.find("b (2 against 2.5)"), std::string::npos) << md;
  EXPECT_NE(AccuracyCsv(report).find(",false\n"), std::string::npos);
}

TEST(AnimatSetTest, ModelFileMayNotNameWhatTheReportCompares) {
  Result<std::vector<Animat>> set =
      LoadAnimatSet(SetWithModelFile("physics { substeps: 4 }"));
  ASSERT_FALSE(set.ok());
  EXPECT_NE(set.status().message().find("physics.substeps"), std::string::npos)
      << set.status().message();
  set =
      LoadAnimatSet(SetWithModelFile("physics { contact_inner_substeps: 2 }"));
  ASSERT_FALSE(set.ok());
  EXPECT_NE(set.status().message().find("physics.contact_inner_substeps"),
            std::string::npos)
      << set.status().message();
  EXPECT_FALSE(LoadAnimatSet(SetWithModelFile("physics { mass: -1 }")).ok());
}

}  // namespace
}  // namespace animat::accuracy
