#include "io/render_identity.h"

#include <fmt/core.h>

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
  static const char* keys[] = {"prism/aovs",          "prism/seed",         "prism/sampler",
                               "prism/integrator",    "prism/maxDepth",     "prism/maxDiffuseDepth",
                               "prism/rrStartDepth",  "prism/clampIndirect", "prism/scene",
                               "prism/camera",        "prism/environment", "prism/lightSampler",
                               "prism/allocation",    "prism/casterShare",   "prism/textureFilter",
                               "prism/split"};
  // Attributes written only away from their defaults (render_attributes) read as those defaults.
  auto text = [](const ExrImage& file, const char* key) {
    std::string t = attribute_text(file, key);
    if (t.empty() && std::string(key) == "prism/split") return std::string("1");
    if (t.empty() && std::string(key) == "prism/allocation") return std::string("uniform");
    return t;
  };
  for (const char* key : keys) {
    const std::string mine = text(image, key), theirs = text(reference, key);
    if (mine != theirs)
      throw InputError(path, key, fmt::format("'{}' differs from {}'s '{}': not a part of the same render", mine,
                                              reference_name, theirs));
  }
}

}  // namespace prism
