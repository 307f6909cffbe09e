// Integrator factory: builds an integrator by name from the render settings.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/integrator.h"
#include "core/render_settings.h"

namespace prism {

// Throws std::invalid_argument naming the known integrators when the name is unknown.
std::unique_ptr<Integrator> make_integrator(const RenderSettings& settings);
std::vector<std::string> integrator_names();

}  // namespace prism
