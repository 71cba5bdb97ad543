// animat figure strip|activity|cells|guidance|fitness|contact-sheet ...
//   -o FILE.svg
//
// The paper's Fig. 4 panels for one animat (snapshot strip, activity along
// the body axes, expansion and contraction of chosen cells), the trials of
// one animat under active guidance, and two figures of an evolution
// (fitness over generations, a contact sheet of the best every N
// generations); docs/analysis.md.
#include <algorithm>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "analysis/analyze.h"
#include "cli/animat_source.h"
#include "cli/commands.h"
#include "cli/run_record.h"
#include "common/evaluation/evaluator.h"
#include "common/evaluation/trace_recorder.h"
#include "common/genome/genome_proto.h"
#include "common/io/proto_file.h"
#include "common/svg/svg.h"
#include "figures/analysis_plots.h"
#include "figures/contact_sheet.h"
#include "figures/guidance_plot.h"
#include "figures/line_plot.h"
#include "figures/snapshot_strip.h"
#include "master/lineage/queries.h"
#include "master/lineage/store.h"

namespace animat::cli {
namespace {

struct Options {
  AnimatSource source;
  std::optional<int64_t> from;
  std::optional<int64_t> to;
  std::string output;
  // strip
  int snapshots = 6;
  std::optional<int64_t> start;
  // activity, cells
  double cycles = 4;
  std::vector<int> cells;
  // fitness, contact-sheet
  std::vector<std::string> dbs;
  std::vector<std::string> records;  // fitness
  int every = 5;
  int columns = 4;
};

Status CheckSvgPath(const std::string& path) {
  if (path.size() < 4 || path.substr(path.size() - 4) != ".svg") {
    return Status::InvalidArgument(path + ": the figure is SVG; name it .svg");
  }
  return Status::Ok();
}

int Write(const std::string& path, const std::string& svg) {
  Status status = WriteFile(path, svg);
  if (!status.ok()) return Fail(status.message());
  return 0;
}

// The analysed animat, for the per-animat figures.
struct Analysed {
  analysis::Recording recording;
  analysis::Analysis analysis;
};

Result<Analysed> LoadAndAnalyse(const Options& o) {
  Result<v1::Trace> trace = LoadAnimatTrace(o.source);
  if (!trace.ok()) return trace.status();
  Result<analysis::Recording> recording = analysis::RecordingFromTrace(*trace);
  if (!recording.ok()) return recording.status();
  Result<analysis::Analysis> result =
      analysis::Analyze(*recording, {.from_step = o.from, .to_step = o.to});
  if (!result.ok()) return result.status();
  return Analysed{std::move(recording).value(), std::move(result).value()};
}

// Writes a figure of one animat and says which window it shows.
int WriteAnimatFigure(const Options& o, const Analysed& a,
                      const std::string& svg) {
  if (Write(o.output, svg) != 0) return 1;
  std::printf("window: %s\n", analysis::DescribeWindow(a.analysis).c_str());
  return 0;
}

int Strip(const Options& o) {
  Result<Analysed> a = LoadAndAnalyse(o);
  if (!a.ok()) return Fail(a.status().message());
  Result<std::string> svg = figures::SnapshotStripSvg(
      a->recording, a->analysis,
      {.snapshots = o.snapshots, .start_step = o.start});
  if (!svg.ok()) return Fail(svg.status().message());
  return WriteAnimatFigure(o, *a, *svg);
}

int Activity(const Options& o) {
  Result<Analysed> a = LoadAndAnalyse(o);
  if (!a.ok()) return Fail(a.status().message());
  return WriteAnimatFigure(
      o, *a,
      figures::LinePlotSvg(figures::ActivityPlot(
          a->analysis, figures::DefaultStepRange(a->analysis, o.cycles))));
}

int Cells(const Options& o) {
  Result<Analysed> a = LoadAndAnalyse(o);
  if (!a.ok()) return Fail(a.status().message());
  const std::vector<int> cells =
      o.cells.empty() ? figures::DefaultCells(a->analysis, 2) : o.cells;
  Result<figures::LinePlot> plot =
      figures::CellsPlot(a->recording, a->analysis, cells,
                         figures::DefaultStepRange(a->analysis, o.cycles));
  if (!plot.ok()) return Fail(plot.status().message());
  return WriteAnimatFigure(o, *a, figures::LinePlotSvg(*plot));
}

// Records the centre of mass of every guidance trial, every `every`-th
// motion step and the last.
class TrialPaths : public EvaluationObserver {
 public:
  TrialPaths(int every, int last) : every_(every), last_(last) {}
  void OnGuidanceTrial(int trial, std::span<const Vec2> sources) override {
    trial_ = trial;
    if (picture_.trials.empty()) {
      for (const Vec2& s : sources) picture_.trials.push_back({s, {}, ""});
    }
  }
  void OnMotionStep(MotionPhase phase, int step, const MotionState& state,
                    std::span<const double>, std::span<const double>) override {
    if (phase != MotionPhase::kMotion || trial_ < 0) return;
    if (step == 0) picture_.start = CentreOfMass(state);
    if (step % every_ == 0 || step == last_) {
      picture_.trials[trial_].path.push_back(CentreOfMass(state));
    }
  }
  figures::GuidancePicture& picture() { return picture_; }

 private:
  int every_, last_;
  int trial_ = -1;
  figures::GuidancePicture picture_;
};

int Guidance(const Options& o) {
  Result<AnimatModel> model = LoadAnimatModel(o.source);
  if (!model.ok()) return Fail(model.status().message());
  const ModelConfig& config = model->config;
  if (!config.guidance.enabled) {
    return Fail(
        "figure guidance needs a configuration with guidance { enabled: "
        "true } (docs/model.md §10.2)");
  }
  TrialPaths paths(o.source.every, config.evaluation.motion_steps);
  EvaluateOptions options;
  options.observed_trial = EvaluateOptions::kAllTrials;
  const EvaluationResult result =
      Evaluate(model->genome, config, &paths, options);
  figures::GuidancePicture& picture = paths.picture();
  if (picture.trials.empty()) {
    return Fail(std::string("no trial ran: ") + EvalStatusName(result.status) +
                (result.reason.empty() ? "" : " (" + result.reason + ")"));
  }
  picture.decay_length = config.guidance.decay_length;
  picture.title =
      "Guidance trials: " + std::string(EvalStatusName(result.status)) +
      (result.fitness ? ", fitness " + svg::Number(*result.fitness, 3)
                      : " (" + result.reason + ")");
  for (size_t k = 0; k < picture.trials.size(); ++k) {
    figures::GuidanceTrialPath& t = picture.trials[k];
    t.caption = "trial " + std::to_string(k);
    if (k < result.source_distances.size()) {
      t.caption += ": ends " + svg::Number(result.source_distances[k], 2) +
                   " radii from its source (" +
                   svg::Number(config.guidance.source_distance, 2) +
                   " at the start)";
    }
  }
  if (Write(o.output, figures::GuidanceSvg(picture)) != 0) return 1;
  std::printf("trials: %zu\n", picture.trials.size());
  return 0;
}

struct StoreRun {
  std::unique_ptr<lineage::Store> store;
  int64_t run = 0;
  lineage::RunRow row;
};

Result<StoreRun> OpenRun(const std::string& db, std::optional<int64_t> run) {
  StoreRun s;
  Result<std::unique_ptr<lineage::Store>> store =
      lineage::Store::OpenForQueries(db);
  if (!store.ok()) return store.status();
  s.store = std::move(store).value();
  Result<int64_t> id = lineage::ChooseRun(*s.store, run);
  if (!id.ok()) return id.status();
  s.run = *id;
  Result<std::vector<lineage::RunRow>> runs = s.store->Runs();
  if (!runs.ok()) return runs.status();
  for (const lineage::RunRow& row : *runs) {
    if (row.run_id == s.run) s.row = row;
  }
  return s;
}

// What a run's fitness measures (docs/model.md §7.4, §10), for an axis.
std::string FitnessUnits(const v1::Config& model) {
  if (model.guidance().enabled()) return "radii closer to the source, mean";
  if (model.evaluation().fitness() ==
      v1::EvaluationConfig::DISTANCE_WITHIN_ENERGY_BUDGET) {
    return "radii swum, within the energy budget";
  }
  return "radii swum";
}

// One run's curves from its completed generations.
figures::FitnessCurves Curves(
    int64_t seed, const v1::Config& model,
    const std::vector<lineage::CompletedGeneration>& rows) {
  figures::FitnessCurves curves;
  curves.label = "seed " + std::to_string(seed);
  curves.units = FitnessUnits(model);
  for (const lineage::CompletedGeneration& g : rows) {
    curves.generation.push_back(g.generation);
    curves.best.push_back(g.stats.best);
    curves.mean.push_back(g.stats.mean);
    curves.median.push_back(g.stats.median);
  }
  return curves;
}

// The runs of --db stores first, then those of --record folders.
int Fitness(const Options& o) {
  if (o.dbs.empty() && o.records.empty()) {
    return Fail("figure fitness needs --db FILE or --record DIR");
  }
  std::vector<figures::FitnessCurves> runs;
  for (const std::string& db : o.dbs) {
    Result<StoreRun> s = OpenRun(db, o.source.run);
    if (!s.ok()) return Fail(s.status().message());
    Result<std::vector<lineage::CompletedGeneration>> rows =
        lineage::CompletedGenerations(*s->store, s->run);
    if (!rows.ok()) return Fail(rows.status().message());
    if (rows->empty()) return Fail(db + ": no completed generation yet");
    runs.push_back(Curves(s->row.seed, s->row.config.model(), *rows));
  }
  for (const std::string& path : o.records) {
    Result<RunRecord> record = ReadRunRecord(path);
    if (!record.ok()) return Fail(record.status().message());
    if (record->generations.empty()) {
      return Fail(path + ": the record holds no completed generation");
    }
    runs.push_back(
        Curves(record->seed, record->config.model(), record->generations));
  }
  return Write(o.output, figures::LinePlotSvg(figures::FitnessPlot(runs)));
}

// Develops and simulates `genome`, for the sheet: the body at the start of
// motion and the path of its centre of mass.
figures::SheetEntry Picture(const v1::Genome& message,
                            const ModelConfig& config) {
  figures::SheetEntry entry;
  Result<Genome> genome = GenomeFromProto(message);
  if (!genome.ok()) return entry;
  TraceRecorder recorder(config, 50);
  Evaluate(*genome, config, &recorder);
  const v1::Trace& trace = recorder.trace();
  bool first = true;
  for (const v1::MotionFrame& frame : trace.frames()) {
    if (frame.phase() != v1::MotionFrame::MOTION || frame.x_size() == 0) {
      continue;
    }
    Vec2 centre;
    for (int i = 0; i < frame.x_size(); ++i) {
      centre += Vec2(frame.x(i), frame.y(i));
      if (first) entry.cells.push_back({frame.x(i), frame.y(i)});
    }
    entry.path.push_back(centre / static_cast<double>(frame.x_size()));
    first = false;
  }
  if (!entry.cells.empty()) {
    for (const v1::Spring& s : trace.body().springs()) {
      entry.springs.push_back(
          {static_cast<int>(s.a()), static_cast<int>(s.b())});
    }
  }
  return entry;
}

std::string FitnessText(const std::optional<double>& fitness) {
  return fitness ? svg::Number(*fitness, 4) : "no fitness";
}

int ContactSheet(const Options& o) {
  if (o.dbs.size() != 1) return Fail("figure contact-sheet needs one --db");
  Result<StoreRun> s = OpenRun(o.dbs[0], o.source.run);
  if (!s.ok()) return Fail(s.status().message());
  ModelConfig config;
  Status status = ConfigFromProto(s->row.config.model(), &config);
  if (!status.ok()) return Fail(status.WithPrefix(o.dbs[0]).message());
  Result<std::vector<lineage::CompletedGeneration>> rows =
      lineage::CompletedGenerations(*s->store, s->run);
  if (!rows.ok()) return Fail(rows.status().message());
  if (rows->empty()) return Fail(o.dbs[0] + ": no completed generation yet");
  std::vector<figures::SheetEntry> entries;
  std::map<uint64_t, figures::SheetEntry> pictures;  // By id: elites repeat.
  for (size_t r = 0; r < rows->size(); ++r) {
    const int generation = (*rows)[r].generation;
    const lineage::GenerationStats& g = (*rows)[r].stats;
    if (generation % o.every != 0 && r + 1 != rows->size()) continue;
    figures::SheetEntry entry;
    if (g.best_id) {
      auto it = pictures.find(*g.best_id);
      if (it == pictures.end()) {
        Result<lineage::IndividualRow> individual =
            s->store->Individual(s->run, *g.best_id);
        if (!individual.ok()) return Fail(individual.status().message());
        it = pictures.emplace(*g.best_id, Picture(individual->genome, config))
                 .first;
      }
      entry = it->second;
      entry.caption = "id " + std::to_string(*g.best_id) + ", fitness " +
                      FitnessText(g.best);
    } else {
      entry.caption = "no individual with a fitness";
    }
    entry.heading = "generation " + std::to_string(generation);
    entries.push_back(std::move(entry));
  }
  const std::string title = "Best individual every " + std::to_string(o.every) +
                            " generations (seed " +
                            std::to_string(s->row.seed) + ")";
  return Write(o.output, figures::ContactSheetSvg(title, entries, o.columns));
}

// The run figures' subcommands: fitness and contact-sheet.
void AddRunFigures(CLI::App* figure, const std::shared_ptr<Options>& o,
                   CLI::App** fitness_out) {
  auto output = [&](CLI::App* sub) {
    sub->add_option("-o,--output", o->output, "Output file (.svg)")->required();
  };
  CLI::App* fitness = figure->add_subcommand(
      "fitness", "Best, mean and median fitness over generations");
  fitness->add_option("--db", o->dbs,
                      "Lineage store (repeat for several runs on one chart)");
  fitness->add_option(
      "--record", o->records,
      "A run record's folder, written by scripts/run_record.py for a run "
      "whose store is not kept (repeatable; drawn after the stores)");
  fitness
      ->add_option("--run", o->source.run,
                   "Run in each store (default: the latest)")
      ->check(IdValidator(kMaxRunId));
  output(fitness);
  CLI::App* sheet = figure->add_subcommand(
      "contact-sheet", "The best individual every N generations");
  sheet->add_option("--db", o->dbs, "Lineage store")->required();
  sheet->add_option("--run", o->source.run, "Run (default: the latest)")
      ->check(IdValidator(kMaxRunId));
  sheet->add_option("--every", o->every, "Every N generations (and the last)")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  sheet->add_option("--columns", o->columns, "Pictures per row")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  output(sheet);
  *fitness_out = fitness;
}

}  // namespace

Command AddFigureCommand(CLI::App& app) {
  auto o = std::make_shared<Options>();
  CLI::App* figure = app.add_subcommand(
      "figure", "SVG figures of an animat or an evolution (docs/analysis.md)");
  figure->require_subcommand(1);
  auto output = [&](CLI::App* sub) {
    sub->add_option("-o,--output", o->output, "Output file (.svg)")->required();
  };
  auto animat = [&](CLI::App* sub) {
    AddAnimatSourceOptions(sub, &o->source);
    sub->add_option("--from", o->from,
                    "First motion step analysed (default: half way, or where "
                    "the animat actuates; docs/analysis.md)");
    sub->add_option("--to", o->to, "Last motion step analysed (default: last)");
    output(sub);
  };
  CLI::App* strip = figure->add_subcommand(
      "strip", "Snapshots over one motion cycle (the paper's Fig. 4.1)");
  animat(strip);
  strip->add_option("--snapshots", o->snapshots, "Snapshots in the cycle")
      ->check(CLI::Range(1, 24))
      ->capture_default_str();
  strip->add_option("--start", o->start,
                    "Motion step the cycle starts at (default: --from)");
  CLI::App* activity = figure->add_subcommand(
      "activity",
      "Mean cell activity along the front-back and left-right axes (Fig. "
      "4.2)");
  animat(activity);
  CLI::App* cells = figure->add_subcommand(
      "cells", "Expansion and contraction of chosen cells (Fig. 4.3)");
  animat(cells);
  cells
      ->add_option("--cells", o->cells,
                   "Cell indices (default: the two strongest drivers)")
      ->delimiter(',');
  for (CLI::App* sub : {activity, cells}) {
    sub->add_option("--cycles", o->cycles,
                    "Periods shown from --from (0: the whole window)")
        ->check(CLI::Range(0.0, 1000.0))
        ->capture_default_str();
  }
  CLI::App* guidance = figure->add_subcommand(
      "guidance",
      "The centre of mass in every guidance trial around its chemical "
      "source (docs/model.md §10.2; the configuration must enable "
      "guidance)");
  AddAnimatSourceOptions(guidance, &o->source);
  output(guidance);
  CLI::App* fitness = nullptr;
  AddRunFigures(figure, o, &fitness);
  return [o, strip, activity, cells, guidance, fitness] {
    Status path = CheckSvgPath(o->output);
    if (!path.ok()) return Fail(path.message());
    if (strip->parsed()) return Strip(*o);
    if (activity->parsed()) return Activity(*o);
    if (cells->parsed()) return Cells(*o);
    if (guidance->parsed()) return Guidance(*o);
    if (fitness->parsed()) return Fitness(*o);
    return ContactSheet(*o);
  };
}

}  // namespace animat::cli
