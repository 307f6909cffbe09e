#include "io/scene_source.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "io/errors.h"
#include "io/gltf_loader.h"

namespace prism {

LoadedScene load_scene_source(const std::string& path, Diagnostics& diag, const EnvironmentSpec& environment) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  LoadedScene out;
  if (ext == ".gltf" || ext == ".glb") {
    out.scene = load_gltf(path, diag);
  } else if (ext == ".json") {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path, "", "no such file");
    return load_job(parse_job_file(path, diag), diag, environment);
  } else {
    throw InputError(path, "", "unknown scene type '" + ext + "' (expected .gltf, .glb or a .json job file)");
  }
  EnvironmentSpec env;
  env.override_with(environment);
  apply_environment(env, out.scene);
  return out;
}

LoadedScene load_job(JobFile job, Diagnostics& diag, const EnvironmentSpec& environment) {
  LoadedScene out;
  if (job.scene) out.scene = load_gltf(*job.scene, diag);
  else out.scene.source = job.path;
  apply_job_edits(job, out.scene);
  EnvironmentSpec env = job.environment;
  env.override_with(environment);
  apply_environment(env, out.scene);
  out.job = std::move(job);
  return out;
}

}  // namespace prism
