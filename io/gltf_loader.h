// glTF 2.0 loading (.gltf with external or data-URI buffers, .glb) into a SceneDesc.
#pragma once

#include <string>
#include <vector>

#include "core/scene_desc.h"
#include "io/diagnostics.h"

namespace prism {

// Loads the default scene (or scene 0) of a glTF or GLB file: node hierarchy, triangle meshes
// (instanced when reused), materials, textures and cameras. Features prism does not render are
// reported once each through `diag`; errors throw InputError naming the file and element.
SceneDesc load_gltf(const std::string& path, Diagnostics& diag);

// The same from bytes already in memory; `base_dir` resolves external buffers and images, and
// an empty `base_dir` means no file system at all (external references are missing files).
SceneDesc load_gltf_from_memory(const std::vector<unsigned char>& bytes, const std::string& base_dir,
                                const std::string& name, Diagnostics& diag);

// Whether prism implements glTF extension `name` (anything else in extensionsRequired is an error).
bool is_supported_gltf_extension(const std::string& name);
// Whether glTF extension `name` only carries metadata, which rendering has no use for.
bool is_metadata_gltf_extension(const std::string& name);

}  // namespace prism
