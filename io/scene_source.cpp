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
    JobFile job = parse_job_file(path, diag);
    if (job.scene) {
      out.scene = load_gltf(*job.scene, diag);
    } else {
      out.scene.source = path;
    }
    apply_job_edits(job, out.scene);
    out.job = std::move(job);
  } else {
    throw InputError(path, "", "unknown scene type '" + ext + "' (expected .gltf, .glb or a .json job file)");
  }
  EnvironmentSpec env = out.job ? out.job->environment : EnvironmentSpec{};
  env.override_with(environment);
  apply_environment(env, out.scene);
  return out;
}

}  // namespace prism
