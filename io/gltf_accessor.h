// Bounds-checked reading of glTF accessors (strides, normalised integers, sparse substitution).
#pragma once

#include <tiny_gltf.h>

#include <cstdint>
#include <string>
#include <vector>

namespace prism {

// Reads accessor `index` as floats, `components` per element, checking that its type has that
// many components and its component type is one of `allowed` (TINYGLTF_COMPONENT_TYPE_*).
// Normalised integers map to [0,1] or [-1,1] as glTF 2.0 §3.11 defines. Throws InputError
// naming `file` and `what` on any range, type or count problem.
std::vector<float> read_accessor_floats(const tinygltf::Model& model, int index, int components,
                                        const std::vector<int>& allowed, const std::string& file,
                                        const std::string& what);

// Reads an index accessor (SCALAR of unsigned byte, short or int).
std::vector<uint32_t> read_accessor_indices(const tinygltf::Model& model, int index, const std::string& file,
                                            const std::string& what);

// The bytes of buffer view `index`, checked against its buffer. Throws InputError.
std::pair<const unsigned char*, size_t> buffer_view_bytes(const tinygltf::Model& model, int index,
                                                          const std::string& file, const std::string& what);

}  // namespace prism
