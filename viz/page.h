// A trace as one self-contained HTML page that replays it: development
// (cells as discs), then equilibration and motion (springs, skin, cells
// coloured by actuation as in the paper's Fig. 4, the centre of mass's
// trail, a scale bar), with play, pause, speed, a scrub bar, the step
// number and the model time.
//
// The page loads nothing: its script, style and data are inline. Its
// controls and the hooks for scripts (window.animat, #step's data
// attributes, the #frame=N fragment) are in docs/formats.md.
//
// Pure function; thread-safe.
#ifndef ANIMAT_VIZ_PAGE_H_
#define ANIMAT_VIZ_PAGE_H_

#include <string>

#include "animat/v1/trace.pb.h"
#include "common/base/status.h"
#include "viz/page_data.h"

namespace animat::viz {

// The page for `trace`. Fails as PageDataJson does.
Result<std::string> RenderPage(const v1::Trace& trace,
                               const PageOptions& options);

}  // namespace animat::viz

#endif  // ANIMAT_VIZ_PAGE_H_
