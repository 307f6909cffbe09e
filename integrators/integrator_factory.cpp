#include "integrators/integrator_factory.h"

#include <stdexcept>

#include "integrators/path_integrator.h"
#include "integrators/whitted_integrator.h"

namespace prism {

std::vector<std::string> integrator_names() { return {"path", "whitted"}; }

std::unique_ptr<Integrator> make_integrator(const RenderSettings& settings) {
  if (settings.integrator == "path")
    return std::make_unique<PathIntegrator>(settings.max_depth, settings.rr_start_depth, settings.max_diffuse_depth,
                                            settings.clamp_indirect);
  if (settings.integrator == "whitted") return std::make_unique<WhittedIntegrator>(settings.max_depth);
  std::string names;
  for (const auto& n : integrator_names()) names += (names.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown integrator '" + settings.integrator + "' (known: " + names + ")");
}

}  // namespace prism
