// Integrator factory: builds an integrator by name from the render settings.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/emitters.h"
#include "core/integrator.h"
#include "core/render_settings.h"

namespace prism {

// Throws std::invalid_argument naming the known integrators when the name is unknown.
std::unique_ptr<Integrator> make_integrator(const RenderSettings& settings);
std::vector<std::string> integrator_names();
// The light samplers by name (the default first); light_sampling throws std::invalid_argument
// naming them for an unknown name.
std::vector<std::string> light_sampler_names();
LightSampling light_sampling(const std::string& name);

}  // namespace prism
