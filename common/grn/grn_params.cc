#include "common/grn/grn_params.h"

#include <string>

#include "common/base/validate.h"

namespace animat {

Status GrnParamsFromProto(const v1::GrnConfig& m, GrnParams* params) {
  GrnParams p = *params;
  if (m.has_weight_max()) p.weight_max = m.weight_max();
  if (m.has_decay_length()) p.decay_length = m.decay_length();
  if (m.has_cutoff()) p.cutoff = m.cutoff();
  if (m.has_dt()) p.dt = m.dt();
  if (m.has_precision()) {
    switch (m.precision()) {
      case v1::GrnConfig::PRECISION_UNSPECIFIED:
        break;
      case v1::GrnConfig::DOUBLE:
        p.precision = Precision::kDouble;
        break;
      case v1::GrnConfig::FLOAT:
        p.precision = Precision::kFloat;
        break;
      default:
        return Status::InvalidArgument("grn.precision: unknown value " +
                                       std::to_string(m.precision()));
    }
  }
  Status status = FirstError({
      RequireNonNegative("grn.weight_max", p.weight_max),
      RequirePositive("grn.decay_length", p.decay_length),
      RequireNonNegative("grn.cutoff", p.cutoff),
      RequirePositive("grn.dt", p.dt),
      RequireInRange("grn.dt", p.dt, 0.0, 1.0),
  });
  if (!status.ok()) return status;
  *params = p;
  return Status::Ok();
}

v1::GrnConfig GrnParamsToProto(const GrnParams& p) {
  v1::GrnConfig m;
  m.set_weight_max(p.weight_max);
  m.set_decay_length(p.decay_length);
  m.set_cutoff(p.cutoff);
  m.set_dt(p.dt);
  m.set_precision(p.precision == Precision::kFloat ? v1::GrnConfig::FLOAT
                                                   : v1::GrnConfig::DOUBLE);
  return m;
}

}  // namespace animat
