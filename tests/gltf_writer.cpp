#include "gltf_writer.h"

#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace prism::test {

using nlohmann::json;

GltfWriter::GltfWriter() {
  json_ = {{"asset", {{"version", "2.0"}}}, {"scene", 0}, {"scenes", json::array({json::object({{"nodes", json::array()}})})},
           {"nodes", json::array()}, {"meshes", json::array()}, {"accessors", json::array()},
           {"bufferViews", json::array()}};
}

int GltfWriter::add_view(const void* data, size_t size) {
  while (bin_.size() % 4) bin_.push_back(0);
  json_["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", bin_.size()}, {"byteLength", size}});
  const auto* p = static_cast<const uint8_t*>(data);
  bin_.insert(bin_.end(), p, p + size);
  return static_cast<int>(json_["bufferViews"].size()) - 1;
}

int GltfWriter::add_accessor(int view, int component_type, size_t count, const std::string& type, bool normalized) {
  json a = {{"bufferView", view}, {"componentType", component_type}, {"count", count}, {"type", type}};
  if (normalized) a["normalized"] = true;
  json_["accessors"].push_back(a);
  return static_cast<int>(json_["accessors"].size()) - 1;
}

int GltfWriter::add_positions(const std::vector<float>& xyz) {
  const int view = add_view(xyz.data(), xyz.size() * sizeof(float));
  const int acc = add_accessor(view, 5126, xyz.size() / 3, "VEC3");
  std::vector<float> lo(3, 1e30f), hi(3, -1e30f);
  for (size_t i = 0; i < xyz.size(); ++i) {
    lo[i % 3] = std::min(lo[i % 3], xyz[i]);
    hi[i % 3] = std::max(hi[i % 3], xyz[i]);
  }
  json_["accessors"][acc]["min"] = lo;
  json_["accessors"][acc]["max"] = hi;
  return acc;
}

int GltfWriter::add_indices(const std::vector<uint32_t>& indices, int component_type) {
  // Little-endian, byte by byte (glTF 2.0 §3.6.2.1).
  const int size = component_type == 5121 ? 1 : component_type == 5123 ? 2 : 4;
  std::vector<uint8_t> bytes;
  for (uint32_t i : indices)
    for (int b = 0; b < size; ++b) bytes.push_back(static_cast<uint8_t>(i >> (8 * b)));
  return add_accessor(add_view(bytes.data(), bytes.size()), component_type, indices.size(), "SCALAR");
}

int GltfWriter::add_mesh(int positions, int indices, int material) {
  json prim = {{"attributes", {{"POSITION", positions}}}};
  if (indices >= 0) prim["indices"] = indices;
  if (material >= 0) prim["material"] = material;
  json_["meshes"].push_back({{"primitives", json::array({prim})}});
  return static_cast<int>(json_["meshes"].size()) - 1;
}

int GltfWriter::add_node(const json& node) {
  json_["nodes"].push_back(node);
  return static_cast<int>(json_["nodes"].size()) - 1;
}

void GltfWriter::set_scene_nodes(const std::vector<int>& nodes) { json_["scenes"][0]["nodes"] = nodes; }

std::string GltfWriter::write(const std::string& dir, const std::string& name, bool glb) {
  json j = json_;
  if (json_["meshes"].empty()) j.erase("meshes");
  if (glb) {
    j["buffers"] = json::array({{{"byteLength", bin_.size()}}});
    std::string text = j.dump();
    while (text.size() % 4) text.push_back(' ');
    std::vector<uint8_t> bin = bin_;
    while (bin.size() % 4) bin.push_back(0);
    const std::string path = dir + "/" + name + ".glb";
    std::ofstream out(path, std::ios::binary);
    auto u32 = [&](uint32_t v) { out.write(reinterpret_cast<const char*>(&v), 4); };
    out.write("glTF", 4);
    u32(2);
    u32(static_cast<uint32_t>(12 + 8 + text.size() + 8 + bin.size()));
    u32(static_cast<uint32_t>(text.size()));
    out.write("JSON", 4);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    u32(static_cast<uint32_t>(bin.size()));
    out.write("BIN\0", 4);
    out.write(reinterpret_cast<const char*>(bin.data()), static_cast<std::streamsize>(bin.size()));
    return path;
  }
  if (bin_.empty()) {  // glTF buffers must not be empty
    j.erase("bufferViews");
    const std::string path = dir + "/" + name + ".gltf";
    std::ofstream(path) << j.dump(1);
    return path;
  }
  j["buffers"] = json::array({{{"byteLength", bin_.size()}, {"uri", name + ".bin"}}});
  std::ofstream(dir + "/" + name + ".bin", std::ios::binary)
      .write(reinterpret_cast<const char*>(bin_.data()), static_cast<std::streamsize>(bin_.size()));
  const std::string path = dir + "/" + name + ".gltf";
  std::ofstream(path) << j.dump(1);
  return path;
}

namespace {

// The directories make_temp_dir made, removed when the test process exits (each test runs in a
// process of its own) unless PRISM_KEEP_TEST_FILES is set, to look at what a failing test wrote.
class TempDirs {
 public:
  ~TempDirs() {
    if (std::getenv("PRISM_KEEP_TEST_FILES")) return;
    std::error_code ignored;
    for (const std::filesystem::path& dir : dirs_) std::filesystem::remove_all(dir, ignored);
  }
  void add(const std::filesystem::path& dir) { dirs_.push_back(dir); }

 private:
  std::vector<std::filesystem::path> dirs_;
};

}  // namespace

std::string make_temp_dir(const std::string& tag) {
  static int counter = 0;
  static TempDirs made;
  const auto dir = std::filesystem::temp_directory_path() /
                   ("prism-test-" + tag + "-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  made.add(dir);
  return dir.string();
}

}  // namespace prism::test
