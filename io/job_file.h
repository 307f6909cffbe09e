// Job files: JSON that names a glTF scene and render settings, adds analytic spheres and
// overrides materials by name.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/render_settings.h"
#include "core/scene_desc.h"
#include "io/diagnostics.h"

namespace prism {

// Material fields a job may set; absent fields keep the glTF value (or the glTF default for a
// material the job defines).
struct MaterialEdit {
  std::string name;
  std::optional<Rgb> base_color;
  std::optional<float> metallic, roughness;
  std::optional<Rgb> emissive;
  std::optional<float> emissive_strength;
  std::optional<bool> double_sided;
  std::optional<float> transmission, ior;
  std::optional<bool> volume;  // a closed volume (refracts, absorbs) rather than a thin sheet
  std::optional<Rgb> attenuation_color;
  std::optional<float> attenuation_distance;
};

struct JobSphere {
  std::string name;
  Vec3 center;
  float radius = 1;
  std::string material;  // a material name (from the glTF or the job), "" = default material
};

// An environment light given by a job file or the command line; unset fields keep what an
// earlier source (job file, then command line) set.
struct EnvironmentSpec {
  std::optional<std::string> map;   // equirectangular image path
  std::optional<Rgb> color;         // constant radiance (without a map) or the map's tint
  std::optional<float> intensity;   // multiplier
  std::optional<float> rotation_degrees;  // about +Y, counter-clockwise seen from above

  bool present() const { return map || color || intensity; }
  void override_with(const EnvironmentSpec& o) {
    if (o.map) map = o.map;
    if (o.color) color = o.color;
    if (o.intensity) intensity = o.intensity;
    if (o.rotation_degrees) rotation_degrees = o.rotation_degrees;
  }
};

// Loads the map (if any) and sets scene.environment. Throws InputError naming the file.
void apply_environment(const EnvironmentSpec& spec, SceneDesc& scene);

struct JobFile {
  std::string path;
  std::optional<std::string> scene;  // glTF path, resolved against the job file's folder
  std::optional<std::string> output, preview;
  std::optional<std::string> pixel_type;   // "float" or "half": the beauty channels' type
  std::optional<std::string> compression;  // "zip", "piz", "dwaa" or "none"
  std::optional<bool> multipart;
  std::optional<bool> stamp;  // write the date and the render time in the header
  std::optional<double> checkpoint_seconds;  // write the progressive image this often
  RenderSettingsOverride settings;
  std::vector<MaterialEdit> materials;
  std::vector<JobSphere> spheres;
  std::vector<PunctualLightDesc> lights;  // added to the scene's own
  EnvironmentSpec environment;
};

// Parses a job file. Type errors throw InputError naming the JSON path and the expected type;
// unknown keys are warned about.
JobFile parse_job_file(const std::string& path, Diagnostics& diag);
JobFile parse_job_json(const std::string& text, const std::string& path, Diagnostics& diag);

// Applies the job's material edits and spheres to a loaded scene. A sphere naming an unknown
// material throws InputError.
void apply_job_edits(const JobFile& job, SceneDesc& scene);

}  // namespace prism
