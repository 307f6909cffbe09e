// Job files: settings, material overrides, analytic spheres, and errors that name the key.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "gltf_writer.h"
#include "io/duration_text.h"
#include "io/errors.h"
#include "io/batch_file.h"
#include "io/job_file.h"
#include "io/scene_source.h"

namespace prism {
namespace {

JobFile parse(const std::string& text, Diagnostics& diag) { return parse_job_json(text, "/jobs/job.json", diag); }

TEST(JobFile, ReadsSettingsAndResolvesPathsAgainstItsFolder) {
  Diagnostics diag;
  const JobFile job = parse(R"({"scene": "scenes/box.gltf", "output": "/abs/out.exr", "resolution": [320, 200],
    "spp": 16, "max_depth": 3, "seed": 42, "camera": 1, "integrator": "path"})", diag);
  EXPECT_EQ(*job.scene, "/jobs/scenes/box.gltf");
  EXPECT_EQ(*job.output, "/abs/out.exr");
  EXPECT_EQ(*job.settings.width, 320);
  EXPECT_EQ(*job.settings.height, 200);
  EXPECT_EQ(*job.settings.spp, 16);
  EXPECT_EQ(*job.settings.max_depth, 3);
  EXPECT_EQ(*job.settings.seed, 42u);
  EXPECT_EQ(*job.settings.camera, "1");
  EXPECT_TRUE(diag.empty());
}

TEST(JobFile, BudgetsAndQualityKnobs) {
  Diagnostics diag;
  const JobFile job = parse(R"({"sampler": "independent", "time": "1m30s", "noise": 0.01, "min_spp": 8,
                                "rr_start_depth": 5, "clamp_indirect": 10, "allocation": "error",
                                "caster_share": 0.5, "texture_filter": "trilinear", "split": 4})", diag);
  RenderSettings s;
  job.settings.apply_to(s);
  EXPECT_EQ(s.sampler, "independent");
  EXPECT_EQ(s.time_budget, 90.0);
  EXPECT_FLOAT_EQ(float(s.noise_target), 0.01f);
  EXPECT_EQ(s.min_spp, 8);
  EXPECT_EQ(s.rr_start_depth, 5);
  EXPECT_EQ(s.clamp_indirect, 10.0f);
  EXPECT_EQ(s.caster_share, 0.5f);
  EXPECT_EQ(s.allocation, "error");
  EXPECT_EQ(s.texture_filter, "trilinear");
  EXPECT_EQ(s.split, 4);
  EXPECT_TRUE(diag.lines().empty());
}

TEST(Durations, AsUsersWriteThem) {
  EXPECT_EQ(parse_duration("90"), 90.0);
  EXPECT_EQ(parse_duration("90s"), 90.0);
  EXPECT_EQ(parse_duration("2.5m"), 150.0);
  EXPECT_EQ(parse_duration("1h30m"), 5400.0);
  EXPECT_EQ(parse_duration("250ms"), 0.25);
  for (const char* bad : {"", "soon", "-5s", "5x", "1m30", " 5s", "nan", "inf"}) EXPECT_FALSE(parse_duration(bad)) << bad;
}

TEST(JobFile, UnknownKeysWarn) {
  Diagnostics diag;
  parse(R"({"spp": 4, "sppp": 5, "materials": {"m": {"colour": [1,0,0]}}})", diag);
  EXPECT_TRUE(diag.contains("$.sppp: unknown key"));
  EXPECT_TRUE(diag.contains("$.materials.m.colour: unknown key"));
}

TEST(JobFile, TypeErrorsNameTheKeyAndType) {
  struct Case {
    const char* json;
    const char* where;
    const char* why;
  };
  const Case cases[] = {
      {R"({"spp": "many"})", "$.spp", "expected an integer"},
      {R"({"spp": 0})", "$.spp", "between 1"},
      {R"({"resolution": [10]})", "$.resolution", "[width, height]"},
      {R"({"seed": -1})", "$.seed", "non-negative"},
      {R"({"time": "soon"})", "$.time", "positive duration"},
      {R"({"time": 0})", "$.time", "positive duration"},
      {R"({"noise": -0.1})", "$.noise", "between"},
      {R"({"split": 0})", "$.split", "between 1 and 64"},
      {R"({"spheres": [{"center": [0, 0], "radius": 1}]})", "$.spheres[0].center", "3 numbers"},
      {R"({"spheres": [{"center": [0, 0, 0], "radius": -1}]})", "$.spheres[0].radius", "between 0"},
      {R"({"spheres": [{"center": [0, 0, 0]}]})", "$.spheres[0]", "radius"},
      {R"({"materials": {"m": {"base_color": [2, 0, 0]}}})", "$.materials.m.base_color[0]", "between 0 and 1"},
      {R"({"materials": {"m": {"double_sided": 1}}})", "$.materials.m.double_sided", "true or false"},
      {R"([1, 2])", "$", "expected an object"},
      {R"({"spp": )", "", "not valid JSON"},
      // Found by fuzz_job_file: nlohmann reports a number past a double as out_of_range, not as
      // a parse error, and that escaped as an internal error (tests/fuzz/regressions/job_file).
      {R"([ { "sFFFFOffset": 2E8888 } ])", "", "not valid JSON: number overflow parsing '2E8888'"},
  };
  for (const Case& c : cases) {
    Diagnostics diag;
    try {
      parse(c.json, diag);
      ADD_FAILURE() << c.json << ": expected an InputError";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("/jobs/job.json"), std::string::npos) << what;
      EXPECT_NE(what.find(c.where), std::string::npos) << what;
      EXPECT_NE(what.find(c.why), std::string::npos) << what;
    }
  }
}

TEST(JobFile, OverridesMaterialsAndAddsSpheres) {
  Diagnostics diag;
  const JobFile job = parse(R"({
    "materials": {"white": {"base_color": [0.2, 0.3, 0.4]}, "lamp": {"emissive": [1, 1, 1], "emissive_strength": 5}},
    "spheres": [{"name": "ball", "center": [0, 1, 0], "radius": 0.5, "material": "lamp"},
                {"center": [2, 1, 0], "radius": 0.25, "material": {"base_color": [1, 0, 0]}},
                {"center": [4, 1, 0], "radius": 0.25}]})", diag);
  SceneDesc scene;
  MaterialDesc white;
  white.name = "white";
  white.emissive = Rgb(0.5f);
  scene.materials.push_back(white);
  apply_job_edits(job, scene);
  ASSERT_EQ(scene.materials.size(), 3u);
  EXPECT_FLOAT_EQ(scene.materials[0].base_color.y, 0.3f);
  EXPECT_FLOAT_EQ(scene.materials[0].emissive.x, 0.5f);  // fields the job leaves alone stay
  ASSERT_EQ(scene.spheres.size(), 3u);
  EXPECT_EQ(scene.spheres[0].name, "ball");
  EXPECT_EQ(scene.materials[scene.spheres[0].material].name, "lamp");
  EXPECT_FLOAT_EQ(scene.materials[scene.spheres[0].material].emissive_strength, 5.0f);
  EXPECT_FLOAT_EQ(scene.materials[scene.spheres[1].material].base_color.x, 1.0f);
  EXPECT_EQ(scene.spheres[2].material, -1);
  EXPECT_TRUE(scene.features().spheres);
  EXPECT_TRUE(scene.features().emitters);
}

TEST(JobFile, GlassMaterialFields) {
  Diagnostics diag;
  const JobFile job = parse(R"({"materials": {"glass": {"transmission": 1, "ior": 1.33, "volume": true,
      "attenuation_color": [0.5, 0.9, 1], "attenuation_distance": 0.2}}})", diag);
  SceneDesc scene;
  apply_job_edits(job, scene);
  ASSERT_EQ(scene.materials.size(), 1u);
  const MaterialDesc& m = scene.materials[0];
  EXPECT_TRUE(m.has_volume());
  EXPECT_FLOAT_EQ(m.ior, 1.33f);
  EXPECT_FLOAT_EQ(m.attenuation_color.x, 0.5f);
  EXPECT_FLOAT_EQ(m.attenuation_distance, 0.2f);
  EXPECT_TRUE(diag.empty());
  EXPECT_THROW(parse(R"({"materials": {"g": {"ior": 0.5}}})", diag), InputError);
  EXPECT_THROW(parse(R"({"materials": {"g": {"attenuation_distance": 0}}})", diag), InputError);
}

TEST(JobFile, PunctualLights) {
  Diagnostics diag;
  const JobFile job = parse(R"({"lights": [
      {"type": "directional", "direction": [0, -2, 0], "color": [1, 0.5, 0.5], "intensity": 3},
      {"type": "spot", "position": [1, 2, 3], "direction": [0, 0, -1], "inner_cone_angle": 0.1, "outer_cone_angle": 0.3}]})",
                            diag);
  SceneDesc scene;
  apply_job_edits(job, scene);
  ASSERT_EQ(scene.lights.size(), 2u);
  EXPECT_EQ(scene.lights[0].type, LightType::Directional);
  EXPECT_NEAR(scene.lights[0].direction.y, -1.0f, 1e-6f);
  EXPECT_FLOAT_EQ(scene.lights[0].intensity.y, 1.5f);
  EXPECT_NEAR(scene.lights[1].cos_outer, std::cos(0.3f), 1e-6f);
  EXPECT_THROW(parse(R"({"lights": [{"type": "laser"}]})", diag), InputError);
  EXPECT_THROW(parse(R"({"lights": [{"type": "point"}]})", diag), InputError);
  EXPECT_THROW(parse(R"({"lights": [{"type": "spot", "position": [0,0,0], "direction": [0,0,1],
      "inner_cone_angle": 0.5, "outer_cone_angle": 0.2}]})", diag), InputError);
}

TEST(JobFile, SphereWithUnknownMaterialIsAnError) {
  Diagnostics diag;
  const JobFile job = parse(R"({"spheres": [{"center": [0, 0, 0], "radius": 1, "material": "nope"}]})", diag);
  SceneDesc scene;
  EXPECT_THROW(apply_job_edits(job, scene), InputError);
}

TEST(SceneSource, LoadsJobWithItsGltfAndRejectsUnknownTypes) {
  const std::string dir = test::make_temp_dir("job");
  test::GltfWriter w;
  const std::vector<float> tri = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  w.doc()["materials"] = nlohmann::json::array({{{"name", "floor"}}});
  w.set_scene_nodes({w.add_node({{"mesh", w.add_mesh(w.add_positions(tri), -1, 0)}})});
  w.write(dir, "scene");
  std::ofstream(dir + "/job.json") << R"({"scene": "scene.gltf", "spp": 3,
      "materials": {"floor": {"base_color": [0, 1, 0]}}, "spheres": [{"center": [0, 0, 1], "radius": 0.5}]})";
  Diagnostics diag;
  const LoadedScene loaded = load_scene_source(dir + "/job.json", diag);
  ASSERT_TRUE(loaded.job.has_value());
  EXPECT_EQ(*loaded.job->settings.spp, 3);
  EXPECT_EQ(loaded.scene.spheres.size(), 1u);
  EXPECT_FLOAT_EQ(loaded.scene.materials[0].base_color.y, 1.0f);
  EXPECT_EQ(loaded.scene.triangle_count(), 1u);
  EXPECT_THROW(load_scene_source(dir + "/scene.obj", diag), InputError);
  EXPECT_THROW(load_scene_source(dir + "/missing.json", diag), InputError);
}

}  // namespace
}  // namespace prism

namespace prism {
namespace {

std::vector<BatchJobText> batch_from(const std::string& text) {
  const std::string path = test::make_temp_dir("batch") + "/batch.json";
  std::ofstream(path) << text;
  return parse_batch_file(path);
}

// Each job is its keys over the defaults, objects merging key by key (RFC 7386), and parses as a
// job file relative to the batch file's folder.
TEST(BatchFile, JobsInheritTheDefaults) {
  const auto jobs = batch_from(R"({"defaults": {"scene": "box.gltf", "spp": 16, "materials": {"red": {"roughness": 0.5}}},
    "jobs": [{"output": "a.exr"}, {"output": "b.exr", "spp": 64, "materials": {"red": {"metallic": 1}}},
             {"output": "c.exr", "spp": null}]})");
  ASSERT_EQ(jobs.size(), 3u);
  EXPECT_EQ(jobs[1].where, "$.jobs[1]");
  Diagnostics diag;
  const JobFile a = parse_job_json(jobs[0].json, "/batches/b.json", diag);
  const JobFile b = parse_job_json(jobs[1].json, "/batches/b.json", diag);
  const JobFile c = parse_job_json(jobs[2].json, "/batches/b.json", diag);
  EXPECT_TRUE(diag.empty());
  EXPECT_EQ(*a.scene, "/batches/box.gltf");
  EXPECT_EQ(*a.output, "/batches/a.exr");
  EXPECT_EQ(*a.settings.spp, 16);
  EXPECT_EQ(*b.settings.spp, 64);
  ASSERT_EQ(b.materials.size(), 1u);
  EXPECT_EQ(*b.materials[0].roughness, 0.5f);  // kept from the defaults
  EXPECT_EQ(*b.materials[0].metallic, 1.0f);   // added by the job
  EXPECT_FALSE(c.settings.spp.has_value());    // null removed the default
  EXPECT_EQ(batch_from(R"([{"output": "x.exr"}])").size(), 1u);  // a bare list, no defaults
}

TEST(BatchFile, MalformedFilesNameTheElement) {
  auto error_of = [](const std::string& text) {
    try {
      batch_from(text);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error_of("{").find("not valid JSON"), std::string::npos);
  EXPECT_NE(error_of(R"({"defaults": {}})").find("$.jobs: missing"), std::string::npos);
  EXPECT_NE(error_of(R"({"jobs": {}})").find("$.jobs: expected a list"), std::string::npos);
  EXPECT_NE(error_of(R"({"jobs": []})").find("no jobs"), std::string::npos);
  EXPECT_NE(error_of(R"({"jobs": [{}, 3]})").find("$.jobs[1]: expected an object"), std::string::npos);
  EXPECT_NE(error_of(R"({"defaults": [], "jobs": [{}]})").find("$.defaults: expected an object"), std::string::npos);
  EXPECT_NE(error_of(R"({"job": [{}]})").find("$.job: unknown key"), std::string::npos);
  EXPECT_NE(error_of("").find("not valid JSON"), std::string::npos);
  EXPECT_NE(error_of(R"({"jobs": [{"spp": 1e999}]})").find("not valid JSON: number overflow"), std::string::npos);
}

}  // namespace
}  // namespace prism
