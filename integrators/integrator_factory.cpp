#include "integrators/integrator_factory.h"

#include <stdexcept>

#include "integrators/path_integrator.h"
#include "integrators/whitted_integrator.h"

namespace prism {

namespace {

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace

std::vector<std::string> integrator_names() { return {"path", "whitted"}; }
std::vector<std::string> light_sampler_names() { return {"tree", "power"}; }

LightSampling light_sampling(const std::string& name) {
  if (name == "tree") return LightSampling::Tree;
  if (name == "power") return LightSampling::Power;
  throw std::invalid_argument("unknown light sampler '" + name + "' (known: " + joined(light_sampler_names()) + ")");
}

std::unique_ptr<Integrator> make_integrator(const RenderSettings& settings) {
  if (settings.split < 1 || settings.split > kMaxSplit)
    throw std::invalid_argument("split " + std::to_string(settings.split) + " is out of range (1 to " +
                                std::to_string(kMaxSplit) + ")");
  if (settings.integrator == "path") {
    auto path = std::make_unique<PathIntegrator>(settings.max_depth, settings.rr_start_depth,
                                                 settings.max_diffuse_depth, settings.clamp_indirect,
                                                 settings.caster_share);
    path->set_split(settings.split);
    return path;
  }
  if (settings.split > 1)
    throw std::invalid_argument("split " + std::to_string(settings.split) + " is the path integrator's; the " +
                                settings.integrator + " integrator does not split paths");
  if (settings.integrator == "whitted") return std::make_unique<WhittedIntegrator>(settings.max_depth);
  throw std::invalid_argument("unknown integrator '" + settings.integrator + "' (known: " + joined(integrator_names()) +
                              ")");
}

}  // namespace prism
