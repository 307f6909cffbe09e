// Loading real glTF files: the project's scenes, the shared assets, and assimp-testmodels when
// installed. Expected counts were read from each file's JSON independently of prism's loader.
#include <gtest/gtest.h>

#include <cctype>
#include <filesystem>

#include "core/scene.h"
#include "io/errors.h"
#include "io/gltf_loader.h"
#include "io/scene_source.h"

namespace prism {
namespace {

struct Expected {
  const char* path;
  size_t triangles, instances, meshes, materials, cameras;
};

void expect_counts(const std::string& root, const Expected& e) {
  const std::string path = root + "/" + e.path;
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is not present";
  Diagnostics diag;
  const SceneDesc s = load_gltf(path, diag);
  EXPECT_EQ(s.triangle_count(), e.triangles) << path;
  EXPECT_EQ(s.instances.size(), e.instances) << path;
  EXPECT_EQ(s.meshes.size(), e.meshes) << path;
  EXPECT_EQ(s.materials.size(), e.materials) << path;
  EXPECT_EQ(s.cameras.size(), e.cameras) << path;
  EXPECT_NO_THROW(Scene{SceneDesc(s)}) << path;  // and it builds
}

// "Duck/Duck.glb" -> "Duck_Duck_glb": readable test names in CTest.
std::string asset_name(const ::testing::TestParamInfo<Expected>& info) {
  std::string name = info.param.path;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

class SceneAssets : public ::testing::TestWithParam<Expected> {};

TEST_P(SceneAssets, LoadsWithTheRightCounts) {
  const std::string p = GetParam().path;
  const std::string root = p.rfind("scenes/", 0) == 0 ? PRISM_SOURCE_DIR : PRISM_SHARED_DIR "/assets";
  expect_counts(root, GetParam());
}

INSTANTIATE_TEST_SUITE_P(
    All, SceneAssets,
    ::testing::Values(Expected{"scenes/cornell-box/cornell-box.gltf", 32, 8, 8, 4, 1},
                      Expected{"scenes/many-lights/many-lights.gltf", 622, 67, 67, 23, 1},
                      Expected{"scenes/window-room/window-room.gltf", 20, 2, 2, 2, 1},
                      Expected{"Box/Box.glb", 12, 1, 1, 1, 0},
                      Expected{"Duck/Duck.glb", 4212, 1, 1, 1, 1},
                      Expected{"CornellBox_lumrapido/cornell_box.glb", 1936, 7, 7, 5, 0},
                      Expected{"2CylinderEngine/2CylinderEngine.glb", 121496, 67, 29, 34, 1},
                      Expected{"TransmissionTest/TransmissionTest.glb", 128775, 22, 22, 14, 1}),
    asset_name);

class AssimpModels : public ::testing::TestWithParam<Expected> {};

TEST_P(AssimpModels, LoadsWithTheRightCounts) { expect_counts("/usr/share/assimp/models/glTF2", GetParam()); }

INSTANTIATE_TEST_SUITE_P(
    All, AssimpModels,
    ::testing::Values(Expected{"BoxTextured-glTF/BoxTextured.gltf", 12, 1, 1, 1, 0},
                      Expected{"BoxTextured-glTF-Binary/BoxTextured.glb", 12, 1, 1, 1, 0},
                      Expected{"BoxTextured-glTF-Embedded/BoxTextured.gltf", 12, 1, 1, 1, 0},
                      Expected{"BoxTextured-glTF-pbrSpecularGlossiness/BoxTextured.gltf", 12, 1, 1, 1, 0},
                      Expected{"cameras/Cameras.gltf", 2, 1, 1, 0, 2},
                      Expected{"2CylinderEngine-glTF-Binary/2CylinderEngine.glb", 121496, 67, 29, 34, 1}),
    asset_name);

// This variant lists KHR_technique_webgl (GLSL shaders from glTF 1.0 days) in extensionsRequired:
// a client without the extension must refuse the file (glTF 2.0 §3.12), so prism reports it.
TEST(AssimpModels, RequiredTechniqueExtensionIsReported) {
  const std::string path = "/usr/share/assimp/models/glTF2/BoxTextured-glTF-techniqueWebGL/BoxTextured.gltf";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is not present";
  Diagnostics diag;
  try {
    load_gltf(path, diag);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("KHR_technique_webgl"), std::string::npos) << e.what();
  }
}

// The 64 lamps are 128 emissive triangles, each lamp's two one quad emitter; the tree has more
// than one leaf, so it weighs lamps by where they are seen from.
TEST(SceneAssets, ManyLightsBuildsALightTreeOverItsLamps) {
  Diagnostics diag;
  const Scene scene(load_gltf(PRISM_SOURCE_DIR "/scenes/many-lights/many-lights.gltf", diag));
  const Emitters& emitters = scene.emitters();
  ASSERT_EQ(emitters.size(), 64u);
  EXPECT_GE(emitters.tree().depth(), 6);  // 64 leaves at least that deep
  EXPECT_LE(emitters.tree().depth(), 12);
  // Under a lamp, that lamp is picked far more often than by its share of power.
  const Vec3 under(-6.0f + 0.75f, 0.0f, -6.0f + 0.75f);  // below lamp (0, 0)
  const int first_lamp = emitters.triangle_emitter(3, 0, 0);  // instances: floor, ceiling, pillars, lamps
  ASSERT_GE(first_lamp, 0);
  EXPECT_EQ(emitters.triangle_emitter(3, 0, 1), first_lamp);
  const float tree_pick = emitters.pick_probability(first_lamp, under - scene.origin(), Vec3(0, 1, 0));
  const float power_pick = emitters.power_pick_probability(first_lamp);
  EXPECT_GT(tree_pick, 10 * power_pick) << "tree " << tree_pick << ", power " << power_pick;
}

TEST(SceneAssets, CornellGlassHasGlassAMirrorAndAnAbsorbingVolume) {
  Diagnostics diag;
  const LoadedScene loaded = load_scene_source(PRISM_SOURCE_DIR "/scenes/cornell-glass/cornell-glass.json", diag);
  const SceneFeatures f = loaded.scene.features();
  EXPECT_TRUE(f.transmission);
  EXPECT_TRUE(f.absorbing_media);
  EXPECT_TRUE(f.spheres);
  ASSERT_EQ(loaded.scene.spheres.size(), 2u);
  const MaterialDesc& glass = loaded.scene.material(loaded.scene.spheres[0].material);
  EXPECT_TRUE(glass.has_volume());
  EXPECT_FLOAT_EQ(glass.ior, 1.5f);
  const MaterialDesc& mirror = loaded.scene.material(loaded.scene.spheres[1].material);
  EXPECT_FLOAT_EQ(mirror.metallic, 1.0f);
  const int tinted = loaded.scene.find_material("tinted_glass");
  ASSERT_GE(tinted, 0);
  EXPECT_TRUE(loaded.scene.materials[tinted].has_volume());
  EXPECT_FLOAT_EQ(loaded.scene.materials[tinted].attenuation_distance, 0.1f);
  EXPECT_TRUE(diag.empty()) << diag.lines().front();
}

TEST(SceneAssets, WindowRoomIsLitOnlyThroughAThinGlassPane) {
  Diagnostics diag;
  const LoadedScene loaded = load_scene_source(PRISM_SOURCE_DIR "/scenes/window-room/window-room.json", diag);
  const int glass = loaded.scene.find_material("window_glass");
  ASSERT_GE(glass, 0);
  EXPECT_FALSE(loaded.scene.materials[glass].has_volume());  // thin-walled: no refraction
  const Scene scene{SceneDesc(loaded.scene)};
  EXPECT_TRUE(scene.emitters().environment().present());
  EXPECT_EQ(scene.emitters().size(), 0u);      // no lamps: the sky is the only light
  EXPECT_TRUE(scene.casters().empty());        // shadow rays cross the pane: nothing to aim at
  EXPECT_EQ(scene.emitters().portals().size(), 2u);  // the sky is sampled through the pane's triangles
  EXPECT_TRUE(diag.empty()) << diag.lines().front();
}

TEST(SceneAssets, CornellBoxJobRendersWithItsSettings) {
  Diagnostics diag;
  const LoadedScene loaded = load_scene_source(PRISM_SOURCE_DIR "/scenes/cornell-box/cornell-box.json", diag);
  ASSERT_TRUE(loaded.job);
  EXPECT_EQ(*loaded.job->settings.spp, 1024);
  EXPECT_EQ(*loaded.job->settings.width, 512);
  EXPECT_TRUE(loaded.scene.features().emitters);
  EXPECT_EQ(loaded.scene.cameras.size(), 1u);
}

}  // namespace
}  // namespace prism
