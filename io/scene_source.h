// Scene sources: a .gltf/.glb file, or a job file (.json) that names one and edits it.
#pragma once

#include <optional>
#include <string>

#include "core/scene_desc.h"
#include "io/diagnostics.h"
#include "io/job_file.h"

namespace prism {

struct LoadedScene {
  SceneDesc scene;
  std::optional<JobFile> job;  // present when the source was a job file
};

// Loads by file type (the extension: .gltf, .glb or .json), with the job's environment, then
// `environment` (e.g. from the command line) over it. Throws InputError.
LoadedScene load_scene_source(const std::string& path, Diagnostics& diag, const EnvironmentSpec& environment = {});
// The same for a job already parsed (one job of a batch).
LoadedScene load_job(JobFile job, Diagnostics& diag, const EnvironmentSpec& environment = {});

}  // namespace prism
