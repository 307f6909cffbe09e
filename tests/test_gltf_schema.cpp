// The glTF schema check: each kind of structural error tinygltf would let through is refused,
// naming the file and the JSON path; valid files (and GLB containers) pass.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstring>
#include <functional>

#include "io/errors.h"
#include "io/gltf_schema.h"

namespace prism {
namespace {

using nlohmann::json;

json triangle() {
  return json::parse(R"({
    "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
    "nodes": [{"mesh": 0, "translation": [0, 0, 0]}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "mode": 4}]}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}],
    "bufferViews": [{"buffer": 0, "byteLength": 36}],
    "buffers": [{"byteLength": 36}],
    "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}, "alphaMode": "MASK"}],
    "textures": [{"source": 0}], "images": [{"uri": "a.png"}]})");
}

std::vector<unsigned char> bytes_of(const std::string& text) { return {text.begin(), text.end()}; }

// The message check_gltf_schema gives for the triangle after `edit`, or "" when it passes.
std::string schema_error(const std::function<void(json&)>& edit) {
  json doc = triangle();
  edit(doc);
  try {
    check_gltf_schema(bytes_of(doc.dump()), "scene.gltf");
    return "";
  } catch (const InputError& e) {
    return e.what();
  }
}

TEST(GltfSchema, AValidFilePasses) { EXPECT_EQ(schema_error([](json&) {}), ""); }

TEST(GltfSchema, EachKindOfErrorNamesTheFileAndThePath) {
  struct Case {
    std::function<void(json&)> edit;
    const char* message;
  };
  const std::vector<Case> cases = {
      {[](json& d) { d.erase("asset"); }, "scene.gltf: $: the required property 'asset' is missing"},
      {[](json& d) { d["meshes"][0]["primitives"] = json::object(); }, "$.meshes[0].primitives: expected an array, got an object"},
      {[](json& d) { d["meshes"][0]["primitives"] = json::array(); }, "$.meshes[0].primitives: expected at least 1 items"},
      {[](json& d) { d["nodes"][0]["mesh"] = -1; }, "$.nodes[0].mesh: expected an index (an integer of 0 or more), got -1"},
      {[](json& d) { d["nodes"][0]["mesh"] = 1; }, "$.nodes[0].mesh: 1 is out of range (the file has 1 meshes)"},
      {[](json& d) { d["nodes"][0]["mesh"] = 0.5; }, "$.nodes[0].mesh: expected an index (an integer of 0 or more), got 0.5"},
      {[](json& d) { d["nodes"][0]["translation"] = {0, 0}; }, "$.nodes[0].translation: expected 3 numbers, got 2"},
      {[](json& d) { d["nodes"][0]["translation"][1] = "y"; }, "$.nodes[0].translation[1]: expected a number, got a string"},
      {[](json& d) { d["nodes"][0]["children"] = {3}; }, "$.nodes[0].children[0]: 3 is out of range (the file has 1 nodes)"},
      {[](json& d) { d["accessors"][0]["componentType"] = 5124; }, "$.accessors[0].componentType: 5124 is not one of"},
      {[](json& d) { d["accessors"][0]["type"] = "VEC5"; }, "$.accessors[0].type: 'VEC5' is not one of SCALAR"},
      {[](json& d) { d["accessors"][0]["count"] = 0; }, "$.accessors[0].count: 0 is out of range (1 or more)"},
      {[](json& d) { d["accessors"][0].erase("count"); }, "$.accessors[0]: the required property 'count' is missing"},
      {[](json& d) { d["bufferViews"][0]["byteStride"] = 2; }, "$.bufferViews[0].byteStride: 2 is out of range (4 to 252)"},
      {[](json& d) { d["meshes"][0]["primitives"][0]["mode"] = 9; }, "$.meshes[0].primitives[0].mode: 9 is out of range (0 to 6)"},
      {[](json& d) { d["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 4; },
       "$.meshes[0].primitives[0].attributes.NORMAL: 4 is out of range (the file has 1 accessors)"},
      {[](json& d) { d["materials"][0]["alphaMode"] = "CLIP"; }, "$.materials[0].alphaMode: 'CLIP' is not one of OPAQUE, MASK, BLEND"},
      {[](json& d) { d["materials"][0]["doubleSided"] = 1; }, "$.materials[0].doubleSided: expected true or false, got 1"},
      {[](json& d) { d["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"] = 2; },
       "baseColorTexture.index: 2 is out of range (the file has 1 textures)"},
      {[](json& d) { d["materials"][0]["extensions"] = json::array(); }, "$.materials[0].extensions: expected an object, got an array"},
      {[](json& d) { d["materials"][0]["extensions"]["KHR_materials_ior"]["ior"] = "glass"; },
       "$.materials[0].extensions.KHR_materials_ior.ior: expected a number, got a string"},
      {[](json& d) { d["textures"][0]["source"] = 1; }, "$.textures[0].source: 1 is out of range (the file has 1 images)"},
      {[](json& d) { d["nodes"][0]["extensions"]["KHR_lights_punctual"]["light"] = 0; },
       "KHR_lights_punctual.light: 0 is out of range (the file has 0 KHR_lights_punctual lights)"},
      {[](json& d) { d["extensionsRequired"] = {"KHR_draco_mesh_compression"}; },
       "$.extensionsRequired: prism does not support KHR_draco_mesh_compression"},
      {[](json& d) {
         d["accessors"][0].erase("bufferView");
         d["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"] = {{"bufferView", 0}};
       }, "$.meshes[0].primitives[0]: the geometry is Draco-compressed"},
      {[](json& d) { d["cameras"] = {{{"type", "fisheye"}}}; }, "$.cameras[0].type: 'fisheye' is not one of perspective, orthographic"},
      {[](json& d) { d["cameras"] = {{{"type", "perspective"}, {"perspective", {{"znear", 0.1}}}}}; },
       "$.cameras[0].perspective: the required property 'yfov' is missing"},
  };
  for (const Case& c : cases) {
    const std::string message = schema_error(c.edit);
    EXPECT_NE(message.find(c.message), std::string::npos) << "expected '" << c.message << "', got '" << message << "'";
  }
}

TEST(GltfSchema, DracoWithUncompressedFallbackPasses) {
  EXPECT_EQ(schema_error([](json& d) {
              d["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"] = {{"bufferView", 0}};
            }),
            "");
}

TEST(GltfSchema, GlbContainersAreReadAndCheckedToo) {
  const std::string text = triangle().dump();
  auto glb = [&](uint32_t version, uint32_t json_length, uint32_t type) {
    const uint32_t header[5] = {0x46546C67u, version, uint32_t(20 + text.size()), json_length, type};
    std::vector<unsigned char> b(sizeof header + text.size());
    std::memcpy(b.data(), header, sizeof header);
    std::memcpy(b.data() + sizeof header, text.data(), text.size());
    return b;
  };
  auto error = [](const std::vector<unsigned char>& b) {
    try {
      check_gltf_schema(b, "scene.glb");
      return std::string();
    } catch (const InputError& e) {
      return std::string(e.what());
    }
  };
  EXPECT_EQ(error(glb(2, uint32_t(text.size()), 0x4E4F534Au)), "");
  EXPECT_NE(error(glb(1, uint32_t(text.size()), 0x4E4F534Au)).find("GLB header: version 1, expected 2"), std::string::npos);
  EXPECT_NE(error(glb(2, uint32_t(text.size()) + 1, 0x4E4F534Au)).find("GLB chunk 0: declares"), std::string::npos);
  EXPECT_NE(error(glb(2, uint32_t(text.size()), 0x004E4942u)).find("the first chunk is not JSON"), std::string::npos);
  EXPECT_NE(error({'g', 'l', 'T', 'F', 2, 0}).find("the file ends inside the header"), std::string::npos);
}

TEST(GltfSchema, JsonSyntaxErrorsGiveThePosition) {
  try {
    check_gltf_schema(bytes_of("{\"asset\": {\"version\": \"2.0\"},\n \"nodes\": [}"), "scene.gltf");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("scene.gltf: not valid JSON: parse error at line 2"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace prism
