// Constants of the genome-to-network map and the network dynamics
// (docs/model.md §2, §3), and their configuration message.
#ifndef ANIMAT_COMMON_GRN_GRN_PARAMS_H_
#define ANIMAT_COMMON_GRN_GRN_PARAMS_H_

#include <vector>

#include "animat/v1/config.pb.h"
#include "common/base/status.h"
#include "common/io/param_table.h"

namespace animat {

// Arithmetic of the network dynamics and signals.
enum class Precision { kDouble, kFloat };

struct GrnParams {
  double weight_max = 10.0;   // Weight at distance 0.
  double decay_length = 1.0;  // w = weight_max * exp(-d / decay_length).
  double cutoff = 3.0;        // Pairs with d >= cutoff do not bind.
  double dt = 0.05;           // Concentration update step.
  // FLOAT by default: docs/accuracy.md measures its effect on fitness at
  // 3.5e-6 (median), ten times below RK4 x1's integration error.
  Precision precision = Precision::kFloat;
};

// Overwrites the fields present in `message` after checking them; on error
// `params` is unchanged and the message names the field ("grn.dt: ...").
Status GrnParamsFromProto(const v1::GrnConfig& message, GrnParams* params);
// Every field set.
v1::GrnConfig GrnParamsToProto(const GrnParams& params);
// The parameters' tables (common/io/param_table.h), which the conversions
// and checks read, and their lines for `animat config defaults`.
ParamTable<GrnParams> GrnParamTable();
EnumTable<GrnParams> GrnEnumTable();
std::vector<ParamDoc> GrnParamDocs();

}  // namespace animat

#endif  // ANIMAT_COMMON_GRN_GRN_PARAMS_H_
