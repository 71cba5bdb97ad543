#include "common/development/development_params.h"

#include "common/base/validate.h"

namespace animat {
Status DevelopmentParamsFromProto(const v1::DevelopmentConfig& m,
                                  DevelopmentParams* params) {
  DevelopmentParams p = *params;
  if (m.has_steps()) p.steps = m.steps();
  if (m.has_max_cells()) p.max_cells = m.max_cells();
  if (m.has_divide_threshold()) p.divide_threshold = m.divide_threshold();
  if (m.has_last_division_step()) p.last_division_step = m.last_division_step();
  if (m.has_min_cells()) p.min_cells = m.min_cells();
  if (m.has_size_gain()) p.size_gain = m.size_gain();
  if (m.has_mechanics_substeps()) p.mechanics_substeps = m.mechanics_substeps();
  if (m.has_stiffness()) p.stiffness = m.stiffness();
  if (m.has_adhesion_ratio()) p.adhesion_ratio = m.adhesion_ratio();
  if (m.has_interaction_range()) p.interaction_range = m.interaction_range();
  if (m.has_mechanics_dt()) p.mechanics_dt = m.mechanics_dt();
  Status status = FirstError({
      RequireIntInRange("development.steps", p.steps, 1, 1000000),
      RequireIntInRange("development.max_cells", p.max_cells, 1, 1024),
      RequireInRange("development.divide_threshold", p.divide_threshold, 0.0,
                     1.0),
      RequireIntInRange("development.last_division_step", p.last_division_step,
                        0, p.steps),
      RequireIntInRange("development.min_cells", p.min_cells, 1, p.max_cells),
      RequireNonNegative("development.size_gain", p.size_gain),
      RequireIntInRange("development.mechanics_substeps", p.mechanics_substeps,
                        0, 1000),
      RequireNonNegative("development.stiffness", p.stiffness),
      RequireNonNegative("development.adhesion_ratio", p.adhesion_ratio),
      RequirePositive("development.interaction_range", p.interaction_range),
      RequirePositive("development.mechanics_dt", p.mechanics_dt),
  });
  if (!status.ok()) return status;
  *params = p;
  return Status::Ok();
}

Status SignalParamsFromProto(const v1::SignalConfig& m, SignalParams* params) {
  SignalParams p = *params;
  if (m.has_maternal_distance()) p.maternal_distance = m.maternal_distance();
  if (m.has_maternal_length()) p.maternal_length = m.maternal_length();
  if (m.has_kernel_length()) p.kernel_length = m.kernel_length();
  if (m.has_delay_length()) p.delay_length = m.delay_length();
  if (m.has_max_delay()) p.max_delay = m.max_delay();
  Status status = FirstError({
      RequireNonNegative("signals.maternal_distance", p.maternal_distance),
      RequirePositive("signals.maternal_length", p.maternal_length),
      RequirePositive("signals.kernel_length", p.kernel_length),
      RequirePositive("signals.delay_length", p.delay_length),
      RequireIntInRange("signals.max_delay", p.max_delay, 0, kMaxSignalDelay),
  });
  if (!status.ok()) return status;
  *params = p;
  return Status::Ok();
}

v1::DevelopmentConfig DevelopmentParamsToProto(const DevelopmentParams& p) {
  v1::DevelopmentConfig m;
  m.set_steps(p.steps);
  m.set_max_cells(p.max_cells);
  m.set_divide_threshold(p.divide_threshold);
  m.set_last_division_step(p.last_division_step);
  m.set_min_cells(p.min_cells);
  m.set_size_gain(p.size_gain);
  m.set_mechanics_substeps(p.mechanics_substeps);
  m.set_stiffness(p.stiffness);
  m.set_adhesion_ratio(p.adhesion_ratio);
  m.set_interaction_range(p.interaction_range);
  m.set_mechanics_dt(p.mechanics_dt);
  return m;
}

v1::SignalConfig SignalParamsToProto(const SignalParams& p) {
  v1::SignalConfig m;
  m.set_maternal_distance(p.maternal_distance);
  m.set_maternal_length(p.maternal_length);
  m.set_kernel_length(p.kernel_length);
  m.set_delay_length(p.delay_length);
  m.set_max_delay(p.max_delay);
  return m;
}

}  // namespace animat
