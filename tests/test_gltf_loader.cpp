// glTF loading from files the tests write: hierarchy, transforms, index types, instancing,
// cameras, materials, extensions and the errors prism must report.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>

#include "core/camera.h"
#include "gltf_writer.h"
#include "io/errors.h"
#include "io/gltf_loader.h"

namespace prism {
namespace {

using nlohmann::json;
using test::GltfWriter;

const std::vector<float> kTriangle = {0, 0, 0, 1, 0, 0, 0, 1, 0};
const std::vector<float> kQuad = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};

class GltfLoaderTest : public ::testing::Test {
 protected:
  std::string dir_ = test::make_temp_dir("gltf");
  Diagnostics diag_;
  SceneDesc load(GltfWriter& w, bool glb = false) { return load_gltf(w.write(dir_, "scene", glb), diag_); }
};

TEST_F(GltfLoaderTest, EveryIndexTypeAndNonIndexed) {
  GltfWriter w;
  const int pos = w.add_positions(kQuad);
  std::vector<int> nodes;
  for (int type : {5121, 5123, 5125}) nodes.push_back(w.add_node({{"mesh", w.add_mesh(pos, w.add_indices({0, 1, 2, 0, 2, 3}, type))}}));
  nodes.push_back(w.add_node({{"mesh", w.add_mesh(w.add_positions(kTriangle))}}));
  w.set_scene_nodes(nodes);
  for (bool glb : {false, true}) {
    const SceneDesc s = load(w, glb);
    ASSERT_EQ(s.meshes.size(), 4u);
    EXPECT_EQ(s.triangle_count(), 7u);
    EXPECT_EQ(s.meshes[0].primitives[0].indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
    EXPECT_EQ(s.meshes[2].primitives[0].indices, s.meshes[0].primitives[0].indices);
    EXPECT_EQ(s.meshes[3].primitives[0].indices, (std::vector<uint32_t>{0, 1, 2}));
    EXPECT_TRUE(s.meshes[0].primitives[0].normals.empty());  // flat: computed from the triangle
  }
}

TEST_F(GltfLoaderTest, ReusedMeshIsInstancedNotCopied) {
  GltfWriter w;
  const int mesh = w.add_mesh(w.add_positions(kTriangle));
  const int a = w.add_node({{"mesh", mesh}, {"translation", {1, 2, 3}}});
  const int b = w.add_node({{"mesh", mesh}, {"scale", {2, 2, 2}}});
  w.set_scene_nodes({a, b});
  const SceneDesc s = load(w);
  EXPECT_EQ(s.meshes.size(), 1u);
  ASSERT_EQ(s.instances.size(), 2u);
  EXPECT_EQ(s.instances[0].mesh, s.instances[1].mesh);
  EXPECT_TRUE(s.features().instancing);
  EXPECT_EQ(s.triangle_count(), 2u);
}

TEST_F(GltfLoaderTest, HierarchyComposesTrsAndMatrices) {
  GltfWriter w;
  const int mesh = w.add_mesh(w.add_positions(kTriangle));
  // child: matrix translating by (0, 0, 5) (column-major); parent: T(1,0,0) R(90 deg about z) S(2).
  const int child = w.add_node({{"mesh", mesh}, {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 5, 1}}});
  const double h = std::sqrt(0.5);
  const int parent = w.add_node({{"children", {child}}, {"translation", {1, 0, 0}}, {"rotation", {0, 0, h, h}}, {"scale", {2, 2, 2}}});
  w.set_scene_nodes({parent});
  const SceneDesc s = load(w);
  ASSERT_EQ(s.instances.size(), 1u);
  // Vertex (1,0,0): +5 z, scale 2 -> (2,0,10), rotate 90 about z -> (0,2,10), translate -> (1,2,10).
  const Vec3 p = s.instances[0].object_to_world.point(Vec3(1, 0, 0));
  EXPECT_NEAR(p.x, 1.0f, 1e-5f);
  EXPECT_NEAR(p.y, 2.0f, 1e-5f);
  EXPECT_NEAR(p.z, 10.0f, 1e-5f);
}

TEST_F(GltfLoaderTest, StripsAndFansBecomeTriangles) {
  GltfWriter w;
  const int pos = w.add_positions(kQuad);
  const int strip = w.add_mesh(pos);
  w.doc()["meshes"][strip]["primitives"][0]["mode"] = 5;
  const int fan = w.add_mesh(pos);
  w.doc()["meshes"][fan]["primitives"][0]["mode"] = 6;
  const int lines = w.add_mesh(pos);
  w.doc()["meshes"][lines]["primitives"][0]["mode"] = 1;
  w.set_scene_nodes({w.add_node({{"mesh", strip}}), w.add_node({{"mesh", fan}}), w.add_node({{"mesh", lines}})});
  const SceneDesc s = load(w);
  ASSERT_EQ(s.meshes.size(), 2u);
  EXPECT_EQ(s.meshes[0].primitives[0].indices, (std::vector<uint32_t>{0, 1, 2, 1, 3, 2}));
  EXPECT_EQ(s.meshes[1].primitives[0].indices, (std::vector<uint32_t>{1, 2, 0, 2, 3, 0}));
  EXPECT_TRUE(diag_.contains("lines primitives are not rendered"));
}

TEST_F(GltfLoaderTest, SeveralPrimitivesPerMeshKeepTheirMaterials) {
  GltfWriter w;
  const int pos = w.add_positions(kTriangle);
  w.doc()["materials"] = json::array({{{"name", "a"}}, {{"name", "b"}}});
  json mesh = {{"primitives", json::array({{{"attributes", {{"POSITION", pos}}}, {"material", 0}},
                                           {{"attributes", {{"POSITION", pos}}}, {"material", 1}}})}};
  w.doc()["meshes"].push_back(mesh);
  w.set_scene_nodes({w.add_node({{"mesh", 0}})});
  const SceneDesc s = load(w);
  ASSERT_EQ(s.meshes[0].primitives.size(), 2u);
  EXPECT_EQ(s.meshes[0].primitives[0].material, 0);
  EXPECT_EQ(s.meshes[0].primitives[1].material, 1);
  EXPECT_EQ(s.materials[1].name, "b");
}

TEST_F(GltfLoaderTest, MaterialFactorsAndEmissiveStrength) {
  GltfWriter w;
  w.doc()["extensionsUsed"] = {"KHR_materials_emissive_strength"};
  w.doc()["materials"] = json::array({{{"name", "lamp"},
                                        {"pbrMetallicRoughness", {{"baseColorFactor", {0.1, 0.2, 0.3, 0.5}}, {"metallicFactor", 0}}},
                                        {"emissiveFactor", {1, 0.5, 0.25}},
                                        {"doubleSided", true},
                                        {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 40}}}}}}});
  w.set_scene_nodes({w.add_node({{"mesh", w.add_mesh(w.add_positions(kTriangle), -1, 0)}})});
  const SceneDesc s = load(w);
  const MaterialDesc& m = s.materials[0];
  EXPECT_FLOAT_EQ(m.base_color.y, 0.2f);
  EXPECT_FLOAT_EQ(m.base_alpha, 0.5f);
  EXPECT_FLOAT_EQ(m.metallic, 0.0f);
  EXPECT_FLOAT_EQ(m.emissive.y, 0.5f);
  EXPECT_FLOAT_EQ(m.emissive_strength, 40.0f);
  EXPECT_TRUE(m.double_sided);
  EXPECT_TRUE(s.features().emitters);
}

TEST_F(GltfLoaderTest, CamerasInNodeOrder) {
  GltfWriter w;
  w.doc()["cameras"] = json::array({{{"name", "wide"}, {"type", "perspective"}, {"perspective", {{"yfov", 1.2}, {"znear", 0.1}, {"aspectRatio", 2.0}}}},
                                     {{"name", "top"}, {"type", "orthographic"}, {"orthographic", {{"xmag", 3}, {"ymag", 2}, {"znear", 0}, {"zfar", 100}}}}});
  const int n0 = w.add_node({{"name", "ortho node"}, {"camera", 1}, {"translation", {0, 10, 0}}});
  const int n1 = w.add_node({{"name", "persp node"}, {"camera", 0}});
  const int mesh = w.add_node({{"mesh", w.add_mesh(w.add_positions(kTriangle))}});
  w.set_scene_nodes({mesh, n1, n0});  // scene order differs from node order
  const SceneDesc s = load(w);
  ASSERT_EQ(s.cameras.size(), 2u);
  EXPECT_EQ(s.cameras[0].name, "top");  // node 0 comes first
  EXPECT_EQ(s.cameras[0].projection, Projection::Orthographic);
  EXPECT_FLOAT_EQ(s.cameras[0].xmag, 3.0f);
  EXPECT_EQ(s.cameras[1].projection, Projection::Perspective);
  EXPECT_FLOAT_EQ(s.cameras[1].yfov, 1.2f);
  EXPECT_FLOAT_EQ(*s.cameras[1].aspect_ratio, 2.0f);
  EXPECT_EQ(select_camera(s, "").name, "top");
  EXPECT_EQ(select_camera(s, "wide").name, "wide");
  EXPECT_EQ(select_camera(s, "persp node").name, "wide");
  EXPECT_EQ(select_camera(s, "1").name, "wide");
  EXPECT_THROW(select_camera(s, "nope"), std::invalid_argument);
  EXPECT_THROW(select_camera(s, "2"), std::invalid_argument);
  int width, height;
  default_resolution(s.cameras[1], width, height);
  EXPECT_EQ(width, 1024);
  EXPECT_EQ(height, 512);
}

TEST_F(GltfLoaderTest, UnsupportedRequiredExtensionIsAnError) {
  GltfWriter w;
  w.doc()["extensionsUsed"] = {"KHR_draco_mesh_compression", "KHR_materials_emissive_strength"};
  w.doc()["extensionsRequired"] = {"KHR_draco_mesh_compression", "KHR_materials_emissive_strength"};
  w.set_scene_nodes({w.add_node({{"mesh", w.add_mesh(w.add_positions(kTriangle))}})});
  try {
    load(w);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("KHR_draco_mesh_compression"), std::string::npos) << what;
    EXPECT_NE(what.find("extensionsRequired"), std::string::npos) << what;
    EXPECT_EQ(what.find("emissive_strength ("), std::string::npos) << what;
  }
}

TEST_F(GltfLoaderTest, UnsupportedFeaturesAreWarnedOnce) {
  GltfWriter w;
  w.doc()["extensionsUsed"] = {"KHR_materials_sheen"};
  json mat = {{"alphaMode", "BLEND"}, {"extensions", {{"KHR_materials_sheen", {{"sheenRoughnessFactor", 1}}}}}};
  w.doc()["materials"] = json::array({mat, mat, mat});
  const int pos = w.add_positions(kTriangle);
  w.set_scene_nodes({w.add_node({{"mesh", w.add_mesh(pos, -1, 0)}}), w.add_node({{"mesh", w.add_mesh(pos, -1, 1)}})});
  load(w);
  const auto lines = diag_.lines();
  int sheen = 0;
  for (const auto& l : lines)
    if (l.find("KHR_materials_sheen") != std::string::npos) ++sheen;
  EXPECT_EQ(sheen, 1);
  EXPECT_FALSE(diag_.contains("alphaMode"));  // BLEND is supported
}

// XMP metadata (KHR_xmp_json_ld; KHR_xmp is its older name) changes nothing a render shows: it is
// accepted, even as required, without a warning.
TEST_F(GltfLoaderTest, MetadataExtensionsAreAcceptedSilently) {
  GltfWriter w;
  w.doc()["extensionsUsed"] = {"KHR_xmp_json_ld", "KHR_xmp"};
  w.doc()["extensionsRequired"] = {"KHR_xmp_json_ld"};
  w.doc()["materials"] = json::array({{{"extensions", {{"KHR_xmp_json_ld", {{"packet", 0}}}}}}});
  w.set_scene_nodes({w.add_node({{"mesh", w.add_mesh(w.add_positions(kTriangle), -1, 0)}})});
  EXPECT_EQ(load(w).triangle_count(), 1u);
  EXPECT_TRUE(diag_.lines().empty()) << diag_.lines().front();
}

TEST_F(GltfLoaderTest, BrokenFilesGiveClearErrors) {
  struct Case {
    const char* name;
    std::function<void(GltfWriter&)> edit;
    const char* message;
  };
  const std::vector<Case> cases = {
      {"index out of range", [](GltfWriter& w) { w.set_scene_nodes({w.add_node({{"mesh", w.add_mesh(w.add_positions(kTriangle), w.add_indices({0, 1, 7}, 5123))}})}); },
       "not below the vertex count"},
      {"node cycle", [](GltfWriter& w) {
         const int a = w.add_node({{"children", {1}}});
         w.add_node({{"children", {a}}});
         w.set_scene_nodes({a});
       }, "cycle"},
      {"accessor past buffer", [](GltfWriter& w) {
         const int pos = w.add_positions(kTriangle);
         w.doc()["accessors"][pos]["count"] = 1000;
         w.set_scene_nodes({w.add_node({{"mesh", w.add_mesh(pos)}})});
       }, "bytes of bufferView"},
      {"bad mesh index", [](GltfWriter& w) { w.set_scene_nodes({w.add_node({{"mesh", 5}})}); }, "$.nodes[0].mesh: 5 is out of range"},
      {"non-finite position", [](GltfWriter& w) {
         const std::vector<float> bad = {0, 0, 0, std::numeric_limits<float>::infinity(), 0, 0, 0, 1, 0};
         const int pos = w.add_positions(bad);
         w.doc()["accessors"][pos].erase("min");  // JSON has no infinity: the bounds would be null,
         w.doc()["accessors"][pos].erase("max");  // which the schema check refuses first
         w.set_scene_nodes({w.add_node({{"mesh", w.add_mesh(pos)}})});
       }, "not finite"},
      {"wrong position type", [](GltfWriter& w) {
         const int pos = w.add_positions(kTriangle);
         w.doc()["accessors"][pos]["type"] = "VEC2";
         w.doc()["accessors"][pos]["count"] = 4;
         w.set_scene_nodes({w.add_node({{"mesh", w.add_mesh(pos)}})});
       }, "expected 3"},
  };
  for (const Case& c : cases) {
    GltfWriter w;
    c.edit(w);
    try {
      load(w);
      ADD_FAILURE() << c.name << ": expected an InputError";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(c.message), std::string::npos) << c.name << ": " << what;
      EXPECT_NE(what.find("scene.gltf"), std::string::npos) << c.name << ": message must name the file: " << what;
    }
  }
}

// A texture whose image is missing or does not decode renders magenta (one texel) with a
// warning naming the image; with strict diagnostics (--strict) it is an error.
TEST_F(GltfLoaderTest, BrokenTexturesRenderMagentaUnlessStrict) {
  for (const char* name : {"image-missing-file.gltf", "image-not-decodable.gltf"}) {
    const std::string path = std::string(PRISM_SOURCE_DIR "/tests/broken/") + name;
    Diagnostics diag;
    const SceneDesc s = load_gltf(path, diag);
    ASSERT_EQ(s.images.size(), 1u) << name;
    EXPECT_EQ(s.images[0].width, 1);
    EXPECT_EQ(s.images[0].texels, (std::vector<float>{1, 0, 1, 1})) << name;
    EXPECT_TRUE(diag.contains("image 0")) << name;
    EXPECT_TRUE(diag.contains("its textures render magenta")) << name;
    Diagnostics strict;
    strict.strict = true;
    EXPECT_THROW(load_gltf(path, strict), InputError) << name;
  }
}

TEST_F(GltfLoaderTest, MissingOrGarbageFilesAreInputErrors) {
  EXPECT_THROW(load_gltf(dir_ + "/absent.gltf", diag_), InputError);
  std::ofstream(dir_ + "/garbage.gltf") << "{ this is not json";
  EXPECT_THROW(load_gltf(dir_ + "/garbage.gltf", diag_), InputError);
  std::ofstream(dir_ + "/short.glb") << "glTF";
  EXPECT_THROW(load_gltf(dir_ + "/short.glb", diag_), InputError);
}

}  // namespace
}  // namespace prism
