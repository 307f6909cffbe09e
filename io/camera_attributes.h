// The camera as OpenEXR header attributes: worldToCamera and worldToNDC (OpenEXR's conventions)
// and the field of view, so compositors can re-project renders.
#pragma once

#include <vector>

#include "core/camera.h"
#include "io/exr_image.h"

namespace prism {

// OpenEXR's worldToCamera (ImfStandardAttributes.h): camera space is left-handed, +x right, +y up
// and +z the viewing direction (RenderMan's), so glTF's camera (looking down -Z, right-handed)
// gains a z flip. Row-vector convention (p' = p M). `camera` in world coordinates.
ExrMatrix world_to_camera_matrix(const Camera& camera);

// OpenEXR's worldToNDC: a world point times this matrix, divided by w, has x and y in [0, 1]
// across the display window, (0, 0) its top-left corner and y growing down.
ExrMatrix world_to_ndc_matrix(const Camera& camera);

// worldToCamera, worldToNDC, prism/projection, prism/fovVertical and prism/fovHorizontal
// (degrees, perspective) or prism/orthoHalfWidth and prism/orthoHalfHeight (orthographic).
std::vector<ExrAttribute> camera_attributes(const Camera& camera);

}  // namespace prism
