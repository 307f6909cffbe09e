// The EXR header record of a render: its settings, budgets and what the budgets reached.
#pragma once

#include <vector>

#include "core/render_settings.h"
#include "core/renderer.h"
#include "io/exr_writer.h"

namespace prism {

// "prism/..." attributes for every setting that decides the image (sampler, seed, integrator,
// depths, Russian roulette, clamping), the budget ("spp", "time", "noise" or "time+noise") with its
// values, and what was reached (spp minimum/mean/maximum, passes, estimated relative error).
// Wall-clock time appears only under a time budget or when `stamp` asks for it (then with the
// date, OpenEXR's capDate), so other renders write reproducible bytes.
std::vector<ExrAttribute> render_attributes(const RenderSettings& settings, const RenderStats& stats, bool stamp = false);

}  // namespace prism
