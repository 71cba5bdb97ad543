// Knock-outs (docs/analysis.md, "Knock-outs"): one animat evaluated intact,
// then once with each input that motion can use silenced, to measure what
// each carries. An experiment on one animat, outside the model: the model's
// evaluations never silence anything.
//
// Pure functions of their arguments; thread-safe.
#ifndef ANIMAT_COMMON_EVALUATION_KNOCKOUT_H_
#define ANIMAT_COMMON_EVALUATION_KNOCKOUT_H_

#include <optional>
#include <vector>

#include "animat/v1/analysis.pb.h"
#include "common/evaluation/evaluator.h"
#include "common/evaluation/model_config.h"
#include "common/genome/genome.h"
#include "common/grn/network.h"

namespace animat {

// The morphogen-making units whose signal motion computes: those with a
// path to an EXPAND or CONTRACT output (model §11.2), as node indices in
// increasing order.
std::vector<int> MotionMorphogenUnits(const Network& network);

// Whether the binding graph (model §2.5) has a path from some CHEMICAL
// input node to `node`.
bool ChemicalReaches(const Network& network, int node);

// Whether unit `node`'s morphogen can reach EXPAND or CONTRACT: some
// G_MORPHOGEN element of the unit binds a region of a node that is, or has
// a path to, an EXPAND or CONTRACT output. `genome` is the one `network`
// was built from under `params`.
bool MorphogenReachesActuators(const Genome& genome, const Network& network,
                               const GrnParams& params, int node);

struct KnockoutRun {
  Knockout knockout;
  // kMorphogen: the genome index of the unit's first element, which names
  // it in `animat grn` (unit_I); otherwise -1.
  int unit_element = -1;
  EvaluationResult result;
  // result's fitness less the intact one's, when both have one.
  std::optional<double> fitness_change;
  // kMorphogen only: ChemicalReaches and MorphogenReachesActuators of the
  // unit; kChemical: whether a CHEMICAL node has a path to EXPAND or
  // CONTRACT (in actuator_path; chemical_path is then true).
  bool chemical_path = false;
  bool actuator_path = false;
};

struct KnockoutReport {
  bool guidance = false;  // Whether the evaluations ran guidance trials.
  EvaluationResult intact;
  // With guidance the CHEMICAL knock-out first; then one per unit of
  // MotionMorphogenUnits, in node order. Empty for an invalid genome.
  std::vector<KnockoutRun> runs;
};

// Evaluates `genome` under `config` (checked by ConfigFromProto) intact and
// with each knock-out, on up to `threads` (>= 1) threads, one evaluation
// each; the report is the same bits for every thread count.
KnockoutReport RunKnockouts(const Genome& genome, const ModelConfig& config,
                            int threads);

// As `animat analyze --knockouts` writes it.
v1::KnockoutAnalysis KnockoutReportToProto(const KnockoutReport& report);

}  // namespace animat

#endif  // ANIMAT_COMMON_EVALUATION_KNOCKOUT_H_
