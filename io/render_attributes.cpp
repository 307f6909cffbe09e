#include "io/render_attributes.h"

#include <ctime>
#include <string>

namespace prism {

std::vector<ExrAttribute> render_attributes(const RenderSettings& s, const RenderStats& stats, bool stamp) {
  const bool timed = s.time_budget > 0, adaptive = s.noise_target > 0;
  const std::string budget = timed && adaptive ? "time+noise" : timed ? "time" : adaptive ? "noise" : "spp";
  std::vector<ExrAttribute> a = {
      {"prism/integrator", s.integrator},
      {"prism/sampler", s.sampler},
      {"prism/lightSampler", s.light_sampler},
      {"prism/textureFilter", s.texture_filter},
      {"prism/seed", std::to_string(s.seed)},
      {"prism/maxDepth", s.max_depth},
      {"prism/maxDiffuseDepth", s.max_diffuse_depth},
      {"prism/rrStartDepth", s.rr_start_depth},
      {"prism/clampIndirect", double(s.clamp_indirect)},
      {"prism/casterShare", double(s.caster_share)},
      {"prism/budget", budget},
      {"prism/spp", int(stats.spp_max)},
      {"prism/sppMin", int(stats.spp_min)},
      {"prism/sppMax", int(stats.spp_max)},
      {"prism/sppMean", stats.spp_mean},
      {"prism/relativeError", stats.relative_error},
      {"prism/nonFiniteSamples", double(stats.nonfinite_samples)},
  };
  if (!s.crop.empty()) a.push_back({"prism/crop", std::to_string(s.crop.x0) + " " + std::to_string(s.crop.y0) + " " +
                                                     std::to_string(s.crop.x1) + " " + std::to_string(s.crop.y1)});
  if (s.first_sample > 0) a.push_back({"prism/firstSample", std::to_string(s.first_sample)});
  if (!s.aovs.empty()) {
    std::string names;
    for (size_t i = 0; i < aov_names().size(); ++i)
      if (s.aovs.has(Aov(i))) names += (names.empty() ? "" : ",") + aov_names()[i];
    a.push_back({"prism/aovs", names});
  }
  // Written only when paths split, so files of renders without it keep their bytes.
  if (s.split > 1) a.push_back({"prism/split", s.split});
  // Written only when samples are shared by error, so files of uniform renders keep their bytes.
  const bool by_error = s.allocation != kUniformAllocation;
  if (by_error) a.push_back({"prism/allocation", s.allocation});
  if (adaptive || by_error) a.push_back({"prism/minSpp", s.min_spp});
  if (timed || adaptive) {
    a.push_back({"prism/sppLimit", s.spp});
    a.push_back({"prism/passes", stats.passes});
  }
  if (timed) a.push_back({"prism/timeBudget", s.time_budget});
  if (timed || stamp) a.push_back({"prism/renderSeconds", stats.seconds});
  if (stamp) {
    // OpenEXR's standard capDate: "YYYY:MM:DD hh:mm:ss", local time.
    const std::time_t now = std::time(nullptr);
    std::tm local{};
    localtime_r(&now, &local);
    char date[32];
    std::strftime(date, sizeof date, "%Y:%m:%d %H:%M:%S", &local);
    a.push_back({"capDate", std::string(date)});
  }
  if (adaptive) {
    a.push_back({"prism/noiseTarget", s.noise_target});
    a.push_back({"prism/convergedFraction", stats.converged_fraction});
  }
  return a;
}

}  // namespace prism
