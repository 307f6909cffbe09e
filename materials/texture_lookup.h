// Texture lookup: bilinear (or nearest) filtering with glTF sampler wrap modes, trilinear across MIP levels.
#pragma once

#include "core/scene_desc.h"

namespace prism {

// Filtered value of `ref` at uv (glTF convention: (0,0) is the top-left of the image). An RGB or
// grey image gives alpha 1; a grey image is replicated to RGB. uv_width > 0 is the width of the
// lookup's footprint in uv units: where it spans more than a texel and the image has MIP levels,
// the two levels around it are read and blended (trilinear); otherwise level 0, bilinear.
Rgba lookup_texture(const SceneDesc& scene, const TextureRef& ref, Vec2 uv, float uv_width = 0);

// Asks the cache for the texels lookup_texture(scene, ref, uv) will read, without waiting for
// them: a path tracer issues these for a packet's hits at once, so their misses overlap.
void prefetch_texture(const SceneDesc& scene, const TextureRef& ref, Vec2 uv, float uv_width = 0);

// Integer texel coordinate i wrapped into [0, n) by `mode`.
int wrap_texel(int i, int n, WrapMode mode);

}  // namespace prism
