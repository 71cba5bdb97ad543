#include "common/grn/grn_params.h"

#include "common/base/validate.h"

namespace animat {
namespace {

using G = GrnParams;

// In the proto's order (docs/model.md §2, §3).
constexpr ParamRow<G> kRows[] = {
    {"weight_max", &G::weight_max, ParamRange::NonNegative(),
     "weight where factor and region coordinates coincide"},
    {"decay_length", &G::decay_length, ParamRange::Positive(),
     "affinity w = weight_max * exp(-d / decay_length)"},
    {"cutoff", &G::cutoff, ParamRange::NonNegative(),
     "pairs at distance >= cutoff do not bind"},
    {"dt", &G::dt, ParamRange::PositiveAtMost(1.0),
     "the concentration update's step"},
};

constexpr EnumPair kPrecisions[] = {
    {static_cast<int>(Precision::kDouble), v1::GrnConfig::DOUBLE},
    {static_cast<int>(Precision::kFloat), v1::GrnConfig::FLOAT},
};

constexpr EnumRow<G> kEnums[] = {
    MakeEnumRow<&G::precision>(
        "precision", kPrecisions,
        "arithmetic of the network and the signals (docs/accuracy.md)"),
};

}  // namespace

Status GrnParamsFromProto(const v1::GrnConfig& m, GrnParams* params) {
  GrnParams p = *params;
  ReadParams<G>(m, kRows, &p);
  Status status = FirstError({
      ReadEnums<G>("grn", m, kEnums, &p),
      CheckParams<G>("grn", p, kRows),
  });
  if (!status.ok()) return status;
  *params = p;
  return Status::Ok();
}

v1::GrnConfig GrnParamsToProto(const GrnParams& p) {
  v1::GrnConfig m;
  WriteParams<G>(p, kRows, &m, kEnums);
  return m;
}

ParamTable<GrnParams> GrnParamTable() { return kRows; }
EnumTable<GrnParams> GrnEnumTable() { return kEnums; }

std::vector<ParamDoc> GrnParamDocs() {
  return DescribeParams<G>("grn", v1::GrnConfig(), kRows, kEnums);
}

}  // namespace animat
