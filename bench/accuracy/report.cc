#include "bench/accuracy/report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "bench/accuracy/stats.h"
#include "bench/accuracy/svg_plot.h"
#include "common/physics/physics_params.h"

namespace animat::accuracy {
namespace {

std::string Format(const char* format, double v) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, v);
  return buffer;
}

// CSV numbers: round-trip precision, "inf" for failures.
std::string CsvNumber(double v) {
  if (std::isinf(v)) return "inf";
  if (std::isnan(v)) return "";
  return Format("%.17g", v);
}

// Markdown errors: two significant digits.
std::string Error(double v) {
  if (std::isinf(v)) return "fail";
  if (std::isnan(v)) return "—";
  if (v == 0.0) return "0";
  return Format("%.1e", v);
}

std::string Ms(double v) {
  if (!std::isfinite(v)) return "—";
  return Format(v < 10 ? "%.2f" : "%.1f", v);
}

std::string Hex(uint64_t v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%016llx",
                static_cast<unsigned long long>(v));
  return buffer;
}

int NonDeterministic(const CandidateResult& c) {
  int count = 0;
  for (const AnimatResult& a : c.animats) count += a.deterministic ? 0 : 1;
  return count;
}

bool Measured(const CandidateResult& c) { return !c.animats.empty(); }

int EvolvedCount(const Report& report) {
  int count = 0;
  for (bool evolved : report.evolved) count += evolved ? 1 : 0;
  return count;
}

// Median and 90th percentile of the fitness error, and the median time,
// over the animats of one kind.
struct KindSummary {
  double median = 0.0, p90 = 0.0, ms = 0.0;
};

KindSummary SummariseKind(const CandidateResult& c, bool evolved) {
  std::vector<double> errors, ms;
  for (const AnimatResult& a : c.animats) {
    if (a.evolved != evolved) continue;
    if (a.converged) errors.push_back(a.fitness_error);
    if (a.status == "ok") ms.push_back(a.ms);
  }
  return {Median(errors), Percentile90(errors), Median(ms)};
}

// The candidates that meet the accuracy rule (docs/model.md §7.6), cheapest
// first, and the choice.
std::string RuleSummary(const Report& report) {
  std::vector<const CandidateResult*> meeting;
  for (const CandidateResult& c : report.candidates) {
    if (c.MeetsRule()) meeting.push_back(&c);
  }
  std::stable_sort(meeting.begin(), meeting.end(),
                   [](const CandidateResult* a, const CandidateResult* b) {
                     return a->ms_median < b->ms_median;
                   });
  if (meeting.empty()) {
    return "**No candidate meets the rule** on this set.\n";
  }
  std::string md = "Meeting the rule, cheapest first:";
  for (size_t i = 0; i < meeting.size(); ++i) {
    const CandidateResult& c = *meeting[i];
    md += std::string(i ? "," : "") + " `" + c.candidate.Label() + "` (" +
          Ms(c.ms_median) + " ms, p90 " + Error(c.fitness_error_p90) + ")";
  }
  md += ". **Chosen: `" + report.rule_choice + "`** (" +
        meeting.front()->candidate.Name() + ").\n";
  return md;
}

}  // namespace

std::string CsvField(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

std::string AccuracyCsv(const Report& report) {
  std::string csv =
      "candidate,integrator,substeps,contact_substeps,contact_inner_substeps,"
      "drag_update,precision,backend,animat,"
      "kind,status,reason,fitness,reference_fitness,fitness_error,"
      "trajectory_error,ms_per_evaluation,cpu_ms_per_evaluation,state_hash,"
      "deterministic,max_overlap,reference_converged\n";
  for (const CandidateResult& c : report.candidates) {
    const Candidate& k = c.candidate;
    const std::string prefix =
        k.Label() + "," + k.integrator + "," + std::to_string(k.substeps) +
        "," + std::to_string(k.contact_substeps) + "," +
        std::to_string(k.contact_inner_substeps) + "," + k.drag_update + "," +
        k.precision + "," + k.backend + ",";
    if (!Measured(c)) {
      csv += prefix + ",,not_loaded," + CsvField(c.error) + ",,,,,,,,,,\n";
      continue;
    }
    for (const AnimatResult& a : c.animats) {
      const bool ok = a.status == "ok";
      csv += prefix + a.animat + "," + (a.evolved ? "evolved" : "random") +
             "," + a.status + "," + CsvField(a.reason) + "," +
             (ok ? CsvNumber(a.fitness) : "") + "," +
             CsvNumber(a.reference_fitness) + "," + CsvNumber(a.fitness_error) +
             "," + CsvNumber(a.trajectory_error) + "," + Format("%.3f", a.ms) +
             "," + Format("%.3f", a.cpu_ms) + "," +
             (ok ? Hex(a.state_hash) : "") + "," +
             (a.deterministic ? "true" : "false") + "," +
             (ok ? CsvNumber(a.max_overlap) : "") + "," +
             (a.converged ? "true" : "false") + "\n";
    }
  }
  return csv;
}

std::string SummaryCsv(const Report& report) {
  std::string csv =
      "candidate,name,integrator,substeps,contact_substeps,"
      "contact_inner_substeps,drag_update,precision,backend,"
      "animats,failures,fitness_error_median,fitness_error_p90,"
      "trajectory_error_median,trajectory_error_p90,ms_per_evaluation_median,"
      "cpu_ms_per_evaluation_median,pareto_front,order_swaps,order_pairs,"
      "error,note,counterpart,counterpart_difference_median,"
      "counterpart_difference_p90,max_overlap,meets_rule,chosen\n";
  for (const CandidateResult& c : report.candidates) {
    const Candidate& k = c.candidate;
    csv += k.Label() + "," + CsvField(k.Name()) + "," + k.integrator + "," +
           std::to_string(k.substeps) + "," +
           std::to_string(k.contact_substeps) + "," +
           std::to_string(k.contact_inner_substeps) + "," + k.drag_update +
           "," + k.precision + "," + k.backend + ",";
    if (!Measured(c)) {
      csv += std::string(",,,,,,,,false,,,") + CsvField(c.error) +
             ",,,,,,false,false\n";
      continue;
    }
    csv +=
        std::to_string(c.animats.size()) + "," + std::to_string(c.failures) +
        "," + CsvNumber(c.fitness_error_median) + "," +
        CsvNumber(c.fitness_error_p90) + "," +
        CsvNumber(c.trajectory_error_median) + "," +
        CsvNumber(c.trajectory_error_p90) + "," + Format("%.3f", c.ms_median) +
        "," + Format("%.3f", c.cpu_ms_median) + "," +
        (c.on_front ? "true" : "false") + "," + std::to_string(c.order_swaps) +
        "," + std::to_string(c.order_pairs) + "," + CsvField(c.error) + "," +
        CsvField(c.note) + "," + c.counterpart + "," +
        (c.counterpart.empty() ? "" : CsvNumber(c.counterpart_median)) + "," +
        (c.counterpart.empty() ? "" : CsvNumber(c.counterpart_p90)) + "," +
        CsvNumber(c.max_overlap) + "," + (c.MeetsRule() ? "true" : "false") +
        "," + (k.Label() == report.rule_choice ? "true" : "false") + "\n";
  }
  return csv;
}

namespace {

// The deepest unjoined overlap under the reference (docs/model.md §8.6):
// what the contact stiffness is chosen by (§7.10).
std::string OverlapSummary(const Report& report) {
  if (report.reference_overlap.empty()) return "";
  size_t worst = 0;
  int over = 0;
  for (size_t a = 0; a < report.reference_overlap.size(); ++a) {
    if (report.reference_overlap[a] > report.reference_overlap[worst]) {
      worst = a;
    }
    over += report.reference_overlap[a] > 0.10;
  }
  std::vector<double> sorted = report.reference_overlap;
  std::sort(sorted.begin(), sorted.end());
  const double p90 = sorted[static_cast<size_t>(0.9 * (sorted.size() - 1))];
  const PhysicsParams defaults;
  return std::string("Contacts: ") + ContactRuleName(defaults.contact_rule) +
         ", k_c " + Format("%g", report.contact_stiffness) +
         ". Deepest unjoined overlap under the reference: " +
         Format("%.1f%%", 100 * report.reference_overlap[worst]) + " (" +
         report.animats[worst] + "), 90th percentile " +
         Format("%.1f%%", 100 * p90) + ", " + std::to_string(over) + " of " +
         std::to_string(sorted.size()) + " animats above 10%.\n\n";
}

// The animats whose reference did not converge, left out of the errors.
std::string ConvergenceSummary(const Report& report) {
  if (report.converged.empty()) return "";
  std::string list;
  int left_out = 0;
  for (size_t a = 0; a < report.converged.size(); ++a) {
    if (report.converged[a]) continue;
    ++left_out;
    list += std::string(list.empty() ? "" : "; ") + report.animats[a] + " (" +
            Format("%.6g", report.reference_fitness[a]) + " against " +
            Format("%.6g", report.check_fitness[a]) + ")";
  }
  const std::string check =
      "Convergence: the reference against RK4 with 32 sub-steps, within " +
      Format("%g", kConvergenceTolerance) + " of its fitness: ";
  if (left_out == 0) return check + "every animat.\n\n";
  return check + std::to_string(report.converged.size() - left_out) + " of " +
         std::to_string(report.converged.size()) +
         " animats. Left out of every error, percentile and order swap (no "
         "fitness to measure against): " +
         list + ".\n\n";
}

}  // namespace

std::string SummaryMarkdown(const Report& report) {
  std::string md;
  md += "### Speed against error\n\n";
  md +=
      "Reference: RK4, 16 sub-steps (h = dt/16), explicit drag, double, "
      "native backend; " +
      Ms(report.reference_ms_median) + " ms per evaluation (median). ";
  const int evolved = EvolvedCount(report);
  md += std::to_string(report.animats.size()) + " animats (" +
        std::to_string(report.animats.size() - evolved) + " random genomes, " +
        std::to_string(evolved) + " evolved: bench/data/accuracy/README.md). ";
  md += std::string("Times: median of ") + std::to_string(report.repeats) +
        " repetition(s) per evaluation, then the median over the animats; " +
        report.machine + ". The whole run took " +
        Format("%.0f", report.total_seconds) + " s" +
        (report.quick ? " (--quick: a smaller run, not the report's figures)"
                      : "") +
        ".\n\n";
  if (!report.excluded.empty()) {
    md += "Left out (reference failed):";
    for (const std::string& e : report.excluded) md += " " + e + ";";
    md += "\n\n";
  }
  md += OverlapSummary(report);
  md += ConvergenceSummary(report);

  md +=
      "| | candidate | fitness error median | p90 | trajectory error "
      "median | p90 | order swaps | deepest overlap | ms / eval | CPU ms | "
      "failures | front | rule |\n";
  md += "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---|\n";
  std::vector<std::string> notes;
  for (const CandidateResult& c : report.candidates) {
    const Candidate& k = c.candidate;
    std::string mark;
    std::string note = c.error;
    if (!c.note.empty()) note += (note.empty() ? "" : "; ") + c.note;
    const int nd = NonDeterministic(c);
    if (nd > 0) {
      note += (note.empty() ? "" : "; ") + std::string("not bit-identical ") +
              "between repetitions on " + std::to_string(nd) + " animats";
    }
    if (!note.empty()) {
      notes.push_back(note);
      mark = std::string(" [") + std::to_string(notes.size()) + "]";
    }
    md += "| `" + k.Label() + "` | " + k.Name() + mark + " | ";
    if (!Measured(c)) {
      md += "— | — | — | — | — | — | — | — | not run | | |\n";
      continue;
    }
    const std::string bold = c.on_front ? "**" : "";
    md += bold + Error(c.fitness_error_median) + bold + " | " +
          Error(c.fitness_error_p90) + " | " +
          Error(c.trajectory_error_median) + " | " +
          Error(c.trajectory_error_p90) + " | " +
          std::to_string(c.order_swaps) + "/" + std::to_string(c.order_pairs) +
          " | " + Format("%.1f%%", 100 * c.max_overlap) + " | " + bold +
          Ms(c.ms_median) + bold + " | " + Ms(c.cpu_ms_median) + " | " +
          std::to_string(c.failures) + " | " + (c.on_front ? "**yes**" : "") +
          " | " +
          (c.candidate.Label() == report.rule_choice ? "**chosen**"
           : c.MeetsRule()                           ? "meets"
                                                     : "") +
          " |\n";
  }
  md += "\n";
  md +=
      "Errors are relative to the reference fitness f_ref of each animat: "
      "fitness error |f − f_ref| / f_ref; trajectory error max over the "
      "motion steps 0, 50, …, 6000 of |d(t) − d_ref(t)| / f_ref, d being "
      "the centre of mass's displacement since the start of motion; both "
      "over the animats whose reference converged (above). Order "
      "swaps: pairs of those animats this candidate ranks in the opposite "
      "order from the reference (what selection would see). A "
      "failed evaluation counts as an infinite error (\"fail\"). The front: "
      "no other candidate without failures is both faster and more "
      "accurate (median time, median fitness error); candidates with a "
      "failure, or not run, or whose option had no effect are not "
      "eligible. Rule (docs/model.md §7.6): every evaluation ok, fitness error "
      "at "
      "most " +
      Format("%g", kRuleP90) +
      " at the 90th percentile, no pair swapped, and no animat's deepest "
      "unjoined overlap above " +
      Format("%.1f%%", 100 * kRuleOverlap) +
      " (docs/model.md §7.10's bound with its margin); the cheapest (median "
      "ms per evaluation) that meets it is chosen as the default, times "
      "within " +
      Format("%g", kRuleTimeTie * 100) +
      "% of the cheapest counting as equal, the smallest 90th-percentile "
      "error deciding among them.\n";
  md += "\n" + RuleSummary(report);
  if (!notes.empty()) {
    md += "\n";
    for (size_t i = 0; i < notes.size(); ++i) {
      md += std::to_string(i + 1) + ". " + notes[i] + "\n";
    }
  }

  md += "\n### The option alone: float arithmetic, Bullet\n\n";
  md +=
      "|f − f_c| / f_ref over the animats, f_c from the candidate that "
      "differs only in that option: the native backend for a Bullet "
      "candidate, double precision for a native float one.\n\n";
  md +=
      "| candidate | against | median | p90 | max "
      "|\n|---|---|---:|---:|---:|\n";
  for (const CandidateResult& c : report.candidates) {
    if (c.counterpart.empty()) continue;
    md += "| `" + c.candidate.Label() + "` | `" + c.counterpart + "` | " +
          Error(c.counterpart_median) + " | " + Error(c.counterpart_p90) +
          " | " + Error(c.counterpart_max) + " |\n";
  }

  if (evolved > 0 && evolved < static_cast<int>(report.animats.size())) {
    md += "\n### Random and evolved animats\n\n";
    md +=
        "Fitness error |f − f_ref| / f_ref and ms per evaluation (medians) "
        "over the " +
        std::to_string(report.animats.size() - evolved) +
        " random genomes and over the " + std::to_string(evolved) +
        " evolved animats apart.\n\n";
    md +=
        "| candidate | random: median | p90 | ms | evolved: median | p90 | "
        "ms |\n|---|---:|---:|---:|---:|---:|---:|\n";
    for (const CandidateResult& c : report.candidates) {
      if (!Measured(c)) continue;
      const KindSummary r = SummariseKind(c, false);
      const KindSummary e = SummariseKind(c, true);
      md += "| `" + c.candidate.Label() + "` | " + Error(r.median) + " | " +
            Error(r.p90) + " | " + Ms(r.ms) + " | " + Error(e.median) + " | " +
            Error(e.p90) + " | " + Ms(e.ms) + " |\n";
    }
  }

  md += "\n### Chaos: runs that differ by one ulp of dt\n\n";
  md +=
      "Each animat run twice, the second with physics.dt one ulp larger "
      "(std::nextafter). Divergence |d(t) − d′(t)| / f_ref at motion step "
      "t, median (90th percentile) over the animats; last column the "
      "fitness difference |f − f′| / f_ref.\n\n";
  if (!report.chaos.empty()) {
    md += "| configuration |";
    for (int step : report.chaos[0].steps) {
      md += std::string(" t = ") + std::to_string(step) + " |";
    }
    md += " fitness |\n|---|";
    for (size_t i = 0; i < report.chaos[0].steps.size(); ++i) md += "---:|";
    md += "---:|\n";
    for (const ChaosResult& chaos : report.chaos) {
      md += "| " + chaos.config + " |";
      for (size_t i = 0; i < chaos.steps.size(); ++i) {
        md += ' ';
        md += Error(chaos.median[i]);
        md += " (";
        md += Error(chaos.p90[i]);
        md += ") |";
      }
      md += std::string(" ") + Error(chaos.fitness_median) + " (" +
            Error(chaos.fitness_p90) + ") |\n";
    }
    md += "\nLargest over the animats:";
    for (const ChaosResult& chaos : report.chaos) {
      md += " " + chaos.config + " " + Error(chaos.max.back()) +
            " at t = " + std::to_string(chaos.steps.back()) + ", fitness " +
            Error(chaos.fitness_max) + ";";
    }
    md += "\n";
  }

  md += "\nAnimats (f_ref):";
  for (size_t i = 0; i < report.animats.size(); ++i) {
    md += std::string(i ? "," : "") + " " + report.animats[i] + " (" +
          Format("%.3g", report.reference_fitness[i]) + ")";
  }
  md += ".\n";
  return md;
}

std::string ReportSvg(const Report& report) {
  std::vector<PlotPoint> points;
  int left_out = 0;
  for (const CandidateResult& c : report.candidates) {
    if (!Measured(c) || !c.error.empty() ||
        !std::isfinite(c.fitness_error_median) ||
        !(c.fitness_error_median > 0.0)) {
      ++left_out;
      continue;
    }
    points.push_back({c.candidate.Label(), c.candidate.Group(), c.ms_median,
                      c.fitness_error_median, c.on_front});
  }
  PlotOptions options;
  options.title = std::string("Speed against error: ") +
                  std::to_string(report.animats.size()) +
                  " animats, reference RK4 ×16";
  options.x_label = "median wall time per evaluation (ms, log scale)";
  options.y_label = "median relative fitness error (log scale)";
  options.note = std::to_string(points.size()) + " candidates plotted" +
                 (left_out ? "; " + std::to_string(left_out) +
                                 " not plotted (not run, no effect, or median "
                                 "error infinite: see summary.md)"
                           : "") +
                 ".";
  options.legend_notes = {"Labels: integrator E = semi-implicit",
                          "Euler, V = velocity Verlet, R = RK4,",
                          "S = SSPRK3, L = Ralston's third",
                          "order, B = Bullet (semi-implicit",
                          "Euler);",
                          "number = sub-steps per step;",
                          "s = stable drag update;",
                          "f = float network arithmetic.",
                          "Front: no other candidate without",
                          "failures is both faster and more",
                          "accurate."};
  return PlotSvg(points, options);
}

}  // namespace animat::accuracy
