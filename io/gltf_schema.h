// Structural check of a glTF 2.0 document's JSON against the core schema, before tinygltf reads it.
#pragma once

#include <string>
#include <vector>

namespace prism {

// Checks the JSON of a .gltf file, or the JSON chunk of a .glb, against the types, required
// properties, enumerations and index ranges of the glTF 2.0 schema (and of the extensions
// prism reads). tinygltf silently skips a property of the wrong type ("primitives" as an
// object, a texture index of -1), which would render a different scene than the file says;
// this refuses it instead. Throws InputError naming `file`, the JSON path ($.meshes[0].primitives)
// and the reason. Also refuses unsupported extensionsRequired and Draco-only geometry.
void check_gltf_schema(const std::vector<unsigned char>& bytes, const std::string& file);

// Whether `bytes` start as a binary glTF container (the GLB magic "glTF").
bool is_glb(const std::vector<unsigned char>& bytes);

}  // namespace prism
