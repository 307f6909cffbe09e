#include "io/render_identity.h"

#include <fmt/core.h>

#include "core/render_settings.h"
#include "io/errors.h"

namespace prism {

std::string attribute_text(const ExrImage& image, const std::string& name) {
  const ExrAttribute* a = image.attribute(name);
  if (!a) return "";
  if (const auto* s = std::get_if<std::string>(&a->second)) return *s;
  if (const auto* i = std::get_if<int>(&a->second)) return std::to_string(*i);
  if (const auto* d = std::get_if<double>(&a->second)) return fmt::format("{}", *d);  // shortest round trip
  return "?";
}

void check_same_render(const ExrImage& image, const std::string& path, const ExrImage& reference,
                       const std::string& reference_name) {
  if (!(image.display == reference.display))
    throw InputError(path, "displayWindow",
                     fmt::format("{}x{} differs from {}'s {}x{}: not a part of the same render", image.display.width(),
                                 image.display.height(), reference_name, reference.display.width(),
                                 reference.display.height()));
  // Each attribute with the text it reads as when absent: render_attributes writes prism/allocation
  // and prism/split only away from their defaults.
  struct Key {
    const char* name;
    std::string absent;
  };
  const RenderSettings defaults;
  const Key keys[] = {{"prism/aovs", ""},          {"prism/seed", ""},           {"prism/sampler", ""},
                      {"prism/integrator", ""},    {"prism/maxDepth", ""},       {"prism/maxDiffuseDepth", ""},
                      {"prism/rrStartDepth", ""},  {"prism/clampIndirect", ""},  {"prism/scene", ""},
                      {"prism/camera", ""},        {"prism/environment", ""},    {"prism/lightSampler", ""},
                      {"prism/allocation", defaults.allocation}, {"prism/casterShare", ""},
                      {"prism/textureFilter", ""}, {"prism/split", std::to_string(defaults.split)}};
  for (const Key& key : keys) {
    const auto text = [&key](const ExrImage& file) {
      const std::string t = attribute_text(file, key.name);
      return t.empty() ? key.absent : t;
    };
    const std::string mine = text(image), theirs = text(reference);
    if (mine != theirs)
      throw InputError(path, key.name, fmt::format("'{}' differs from {}'s '{}': not a part of the same render",
                                                   mine, reference_name, theirs));
  }
}

}  // namespace prism
