#include "core/sampler_factory.h"

#include <stdexcept>

#include "core/sobol_sampler.h"

namespace prism {

std::vector<std::string> sampler_names() { return {"sobol", "independent"}; }

bool sampler_is_stratified(const std::string& name) { return name == "sobol"; }

std::unique_ptr<Sampler> make_sampler(const std::string& name, uint64_t seed) {
  if (name == "sobol") return std::make_unique<SobolSampler>(seed);
  if (name == "independent") return std::make_unique<IndependentSampler>(seed);
  std::string names;
  for (const auto& n : sampler_names()) names += (names.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown sampler '" + name + "' (known: " + names + ")");
}

std::vector<std::unique_ptr<Sampler>> make_lane_samplers(const std::string& name, uint64_t seed, int count) {
  std::vector<std::unique_ptr<Sampler>> samplers;
  if (name == "sobol") {
    auto cache = std::make_shared<SobolSeedCache>(seed, count);
    for (int k = 0; k < count; ++k) samplers.push_back(std::make_unique<SobolSampler>(cache));
  } else {
    for (int k = 0; k < count; ++k) samplers.push_back(make_sampler(name, seed));
  }
  return samplers;
}

}  // namespace prism
