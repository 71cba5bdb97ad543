// The animats of a strategy clustering (analysis/strategy_clusters.h) on
// their first two principal components: each a marker filled with its
// cluster's colour and shaped by its strategy label (turtle a square,
// shark a triangle, worm a diamond, jellyfish a disc, other a ring),
// numbered beside it; a legend of both, and a key of the numbers' names.
//
// In the SVG each animat is a <g class="animat" data-name="…"
// data-label="…" data-cluster="k"> holding one element of class "marker"
// and its number, a <text class="number"> (1, 2, … in the order given);
// the key is a <g class="key"> of <text class="key">, "number  name".
// Pure function; thread-safe.
#ifndef ANIMAT_FIGURES_CLUSTER_PLOT_H_
#define ANIMAT_FIGURES_CLUSTER_PLOT_H_

#include <string>

#include "analysis/strategy_clusters.h"

namespace animat::figures {

std::string ClusterPlotSvg(const analysis::StrategyClustering& clustering,
                           const std::string& title);

}  // namespace animat::figures

#endif  // ANIMAT_FIGURES_CLUSTER_PLOT_H_
