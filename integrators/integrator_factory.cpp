#include "integrators/integrator_factory.h"

#include <stdexcept>

#include "integrators/path_integrator.h"

namespace prism {

std::vector<std::string> integrator_names() { return {"path"}; }

std::unique_ptr<Integrator> make_integrator(const RenderSettings& settings) {
  if (settings.integrator == "path") return std::make_unique<PathIntegrator>(settings.max_depth, settings.rr_start_depth);
  std::string names;
  for (const auto& n : integrator_names()) names += (names.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown integrator '" + settings.integrator + "' (known: " + names + ")");
}

}  // namespace prism
