// Constants of development and signalling (docs/model.md §4, §5), and their
// configuration messages.
#ifndef ANIMAT_COMMON_DEVELOPMENT_DEVELOPMENT_PARAMS_H_
#define ANIMAT_COMMON_DEVELOPMENT_DEVELOPMENT_PARAMS_H_

#include <vector>

#include "animat/v1/config.pb.h"
#include "common/base/status.h"
#include "common/io/param_table.h"

namespace animat {

// Longest signal delay the history ring can hold (steps).
inline constexpr int kMaxSignalDelay = 127;

struct DevelopmentParams {
  int steps = 400;                 // Development steps.
  int max_cells = 32;              // Division stops at this many cells.
  double divide_threshold = 0.9;   // DIVIDE value that triggers division.
  int last_division_step = 300;    // A division at this step or later fails.
  int min_cells = 3;               // Fewer cells at the end fail.
  double size_gain = 0.5;          // Daughter radius 1 + size_gain * SIZE.
  int mechanics_substeps = 5;      // Mechanics sub-steps per step.
  double stiffness = 1.0;          // k_dev, force per radius of overlap.
  double adhesion_ratio = 0.3;     // Adhesion stiffness / k_dev.
  double interaction_range = 1.2;  // Pairs interact while d < range * s.
  double mechanics_dt = 0.1;       // x += F * mechanics_dt per sub-step.
};

struct SignalParams {
  double maternal_distance = 10.0;  // Sources' distance from the origin.
  double maternal_length = 10.0;    // Maternal value exp(-d / length).
  double kernel_length = 3.0;       // K(d) = exp(-d / kernel_length).
  double delay_length = 0.25;       // Delay floor(d / delay_length + 0.5).
  int max_delay = kMaxSignalDelay;  // Steps, in [0, kMaxSignalDelay].
};

// Overwrite the fields present after checking them; on error the params
// are unchanged and the message names the field ("development.steps: ...").
Status DevelopmentParamsFromProto(const v1::DevelopmentConfig& message,
                                  DevelopmentParams* params);
Status SignalParamsFromProto(const v1::SignalConfig& message,
                             SignalParams* params);
// Every field set.
v1::DevelopmentConfig DevelopmentParamsToProto(const DevelopmentParams& p);
v1::SignalConfig SignalParamsToProto(const SignalParams& p);
// The parameters' tables (common/io/param_table.h), which the conversions
// and checks read, and the lines of both ("development.*", "signals.*")
// for `animat config defaults`.
ParamTable<DevelopmentParams> DevelopmentParamTable();
ParamTable<SignalParams> SignalParamTable();
std::vector<ParamDoc> DevelopmentParamDocs();

}  // namespace animat

#endif  // ANIMAT_COMMON_DEVELOPMENT_DEVELOPMENT_PARAMS_H_
