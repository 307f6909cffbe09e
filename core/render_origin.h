// The render origin: prism renders in coordinates centred on the scene, not on the file's origin.
#pragma once

#include "core/scene_desc.h"

namespace prism {

// Where to put the origin of the coordinates a scene is rendered in: the centre of its bounds
// when the scene lies farther from the file's origin than its own size, else the origin itself.
// Floats near a coordinate c are spaced c x 2^-23 apart, and every ray offset is a multiple of
// that spacing; a one-metre room placed 1e5 m away would render with hit points on a 1 cm grid
// and offsets of 20 cm, a tenth of the room. Large-world renderers rebase the same way.
Vec3 choose_render_origin(const SceneDesc& scene);

// Makes every position in `scene` relative to `origin` (instances, spheres, lights, cameras);
// transforms compose in double, so a vertex near the new origin keeps all its precision.
void move_origin(SceneDesc& scene, const Vec3& origin);

}  // namespace prism
