// GltfWriter: builds small glTF files for loader tests (JSON with a .bin beside it, or a .glb).
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace prism::test {

class GltfWriter {
 public:
  GltfWriter();
  nlohmann::json& doc() { return json_; }

  // Appends bytes to the binary buffer as a new bufferView; returns its index.
  int add_view(const void* data, size_t size);
  // Adds an accessor over a view; returns its index.
  int add_accessor(int view, int component_type, size_t count, const std::string& type, bool normalized = false);
  // Convenience: float VEC3 positions and index accessors of a given component type.
  int add_positions(const std::vector<float>& xyz);
  int add_indices(const std::vector<uint32_t>& indices, int component_type);
  // Adds a mesh with one TRIANGLES primitive; returns the mesh index.
  int add_mesh(int positions, int indices = -1, int material = -1);
  int add_node(const nlohmann::json& node);  // returns the node index
  void set_scene_nodes(const std::vector<int>& nodes);

  // Writes <dir>/<name>.gltf and <name>.bin, or <dir>/<name>.glb; returns the path.
  std::string write(const std::string& dir, const std::string& name, bool glb = false);

 private:
  nlohmann::json json_;
  std::vector<uint8_t> bin_;
};

// A fresh empty directory under the system temp folder, removed with what it holds when the process exits.
std::string make_temp_dir(const std::string& tag);

}  // namespace prism::test
