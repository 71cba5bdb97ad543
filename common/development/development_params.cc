#include "common/development/development_params.h"

#include "common/base/validate.h"
#include "common/io/param_table.h"

namespace animat {
namespace {

using D = DevelopmentParams;
using S = SignalParams;

// In the proto's order (docs/model.md §4). The bounds that name another
// field are checked after the table's.
constexpr ParamRow<D> kDevelopment[] = {
    {"steps", &D::steps, ParamRange::Closed(1, 1000000), "development steps"},
    {"max_cells", &D::max_cells, ParamRange::Closed(1, 1024),
     "division stops at this many cells"},
    {"divide_threshold", &D::divide_threshold, ParamRange::Closed(0.0, 1.0),
     "a cell divides when its DIVIDE value is at least this"},
    {"last_division_step", &D::last_division_step,
     ParamRange::Closed(0, 1000000),
     "a division at this step or later fails the embryo; at most steps"},
    {"min_cells", &D::min_cells, ParamRange::Closed(1, 1024),
     "fewer cells at the end fail the embryo; at most max_cells"},
    {"size_gain", &D::size_gain, ParamRange::NonNegative(),
     "daughter radius 1 + size_gain * SIZE (radii)"},
    {"mechanics_substeps", &D::mechanics_substeps, ParamRange::Closed(0, 1000),
     "mechanics sub-steps per development step"},
    {"stiffness", &D::stiffness, ParamRange::NonNegative(),
     "repulsion k_dev (force per radius of overlap)"},
    {"adhesion_ratio", &D::adhesion_ratio, ParamRange::NonNegative(),
     "adhesion stiffness as a fraction of k_dev"},
    {"interaction_range", &D::interaction_range, ParamRange::Positive(),
     "pairs interact while d < range * (r_i + r_j)"},
    {"mechanics_dt", &D::mechanics_dt, ParamRange::Positive(),
     "overdamped step: x += F * mechanics_dt"},
};

// In the proto's order (docs/model.md §5).
constexpr ParamRow<S> kSignals[] = {
    {"maternal_distance", &S::maternal_distance, ParamRange::NonNegative(),
     "the maternal sources' distance from the origin (radii)"},
    {"maternal_length", &S::maternal_length, ParamRange::Positive(),
     "maternal value exp(-|x - s| / maternal_length) (radii)"},
    {"kernel_length", &S::kernel_length, ParamRange::Positive(),
     "endogenous kernel K(d) = exp(-d / kernel_length) (radii)"},
    {"delay_length", &S::delay_length, ParamRange::Positive(),
     "delay floor(d / delay_length + 0.5) steps (radii per step)"},
    {"max_delay", &S::max_delay, ParamRange::Closed(0, kMaxSignalDelay),
     "the longest delay (steps)"},
};

}  // namespace

Status DevelopmentParamsFromProto(const v1::DevelopmentConfig& m,
                                  DevelopmentParams* params) {
  DevelopmentParams p = *params;
  ReadParams<D>(m, kDevelopment, &p);
  Status status = FirstError({
      CheckParams<D>("development", p, kDevelopment),
      RequireIntInRange("development.last_division_step", p.last_division_step,
                        0, p.steps),
      RequireIntInRange("development.min_cells", p.min_cells, 1, p.max_cells),
  });
  if (!status.ok()) return status;
  *params = p;
  return Status::Ok();
}

Status SignalParamsFromProto(const v1::SignalConfig& m, SignalParams* params) {
  SignalParams p = *params;
  ReadParams<S>(m, kSignals, &p);
  Status status = CheckParams<S>("signals", p, kSignals);
  if (!status.ok()) return status;
  *params = p;
  return Status::Ok();
}

v1::DevelopmentConfig DevelopmentParamsToProto(const DevelopmentParams& p) {
  v1::DevelopmentConfig m;
  WriteParams<D>(p, kDevelopment, &m);
  return m;
}

v1::SignalConfig SignalParamsToProto(const SignalParams& p) {
  v1::SignalConfig m;
  WriteParams<S>(p, kSignals, &m);
  return m;
}

ParamTable<DevelopmentParams> DevelopmentParamTable() { return kDevelopment; }
ParamTable<SignalParams> SignalParamTable() { return kSignals; }

std::vector<ParamDoc> DevelopmentParamDocs() {
  std::vector<ParamDoc> docs =
      DescribeParams<D>("development", v1::DevelopmentConfig(), kDevelopment);
  for (ParamDoc& doc :
       DescribeParams<S>("signals", v1::SignalConfig(), kSignals)) {
    docs.push_back(std::move(doc));
  }
  return docs;
}

}  // namespace animat
