// The features a swimming strategy is judged on (analysis/strategy.h),
// measured from a recording and its analysis over the analysis window:
// symmetry and phase lags of actuation between the sides, and the symmetry
// of their rectified activity; synchrony and stroke shape of the whole
// body, and its stroke against its pointed end; pulses of speed; the mean
// body's shape and how far its back swings (docs/analysis.md, "Strategy",
// defines each). Pure function; deterministic; thread-safe.
#ifndef ANIMAT_ANALYSIS_STRATEGY_FEATURES_H_
#define ANIMAT_ANALYSIS_STRATEGY_FEATURES_H_

#include "analysis/analyze.h"
#include "analysis/recording.h"
#include "analysis/strategy.h"

namespace animat::analysis {

// `analysis` must come from Analyze(`recording`, ...) (its window, axes
// and components); its `strategy` is not read. Features that are
// undefined for this animat are left absent.
StrategyFeatures MeasureStrategyFeatures(const Recording& recording,
                                         const Analysis& analysis);

}  // namespace animat::analysis

#endif  // ANIMAT_ANALYSIS_STRATEGY_FEATURES_H_
