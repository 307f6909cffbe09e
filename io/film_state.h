// A film inside an EXR: exact accumulator channels (prism.state.*) for resuming and merging, and
// rebuilding a film from a prism EXR's layers when a file has no such channels.
#pragma once

#include <string>

#include "core/film.h"
#include "io/exr_image.h"

namespace prism {

// Adds uint channels "prism.state.<name>" holding every accumulator of `film` bit for bit (a
// double as two uint halves): the beauty sums, squared sums and counts, the averaged AOV sums, the
// Halves when the film tracks them, the nearest hit, and every Cryptomatte id count (the layers
// keep only the top ranks).
void add_film_state(const Film& film, ExrImage& image);

// Whether `image` carries the channels add_film_state writes.
bool has_film_state(const ExrImage& image);

// The film a prism EXR holds, over its data window, with the AOVs its "prism/aovs" attribute
// names: exact from prism.state.* channels when present; otherwise rebuilt from the layers
// (sums = mean x count, squared sums from the variance layer when there is one; counts from the
// spp layer or the prism/sppMax attribute), which is exact to float rounding. Throws InputError
// naming `path` when the file lacks what it needs.
Film film_from_image(const ExrImage& image, const std::string& path);

}  // namespace prism
