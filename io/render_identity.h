// Which EXR header attributes make two files parts of one render (sample slices, crops, a stopped
// render and its continuation), and the check that they agree.
#pragma once

#include <string>

#include "io/exr_image.h"

namespace prism {

// An attribute's value as text: strings as they are, numbers in full precision, "" when absent.
std::string attribute_text(const ExrImage& image, const std::string& name);

// Throws InputError naming `path` and the first attribute that decides the pixels (AOVs, seed,
// sampler, integrator, depths, Russian roulette, clamping, scene, camera, environment) and that
// differs between `image` and `reference` (described as `reference_name` in the message), or
// their display windows when those differ.
void check_same_render(const ExrImage& image, const std::string& path, const ExrImage& reference,
                       const std::string& reference_name);

}  // namespace prism
