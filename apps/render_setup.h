// Preparing a render: the scene source loaded, settings resolved (defaults, job file, command
// line), the camera chosen, and the Embree scene built; shared by render, converge and bench.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "apps/render_command.h"
#include "core/camera.h"
#include "core/film.h"
#include "core/renderer.h"
#include "core/render_settings.h"
#include "core/scene.h"
#include "io/job_file.h"
#include "io/scene_source.h"

namespace prism {

struct PreparedRender {
  std::string scene_path;
  std::optional<JobFile> job;
  RenderSettings settings;
  CameraDesc camera;
  SceneDesc desc;                // moved into `scene` by build_scene
  std::unique_ptr<Scene> scene;  // null until build_scene
};

// Loads the scene source and resolves settings and camera; prints the loader's warnings unless
// quiet. Throws UsageError for bad options and InputError for bad files.
PreparedRender prepare_render(const RenderOptions& options);

// Options that render a job of a job list (a batch's, or a job file's own): the job parsed already,
// named by its scene, else by its place in the list ("batch.json#$.jobs[2]").
RenderOptions job_render_options(JobFile job, const std::string& list_file, const std::string& where);

// Builds the Embree scene (and warns, unless quiet, when nothing emits light).
void build_scene(PreparedRender& render, bool quiet);

// The settings of a converged reference for renders made with `settings`: `spp` samples and
// another seed, so the reference's error is independent of theirs (converge and bench).
RenderSettings reference_settings(RenderSettings settings, int spp);
// Writes a reference render of `render`'s scene to `path` (OpenEXR), with the settings and
// statistics that made it in its header.
void write_reference(const std::string& path, const PreparedRender& render, const RenderSettings& settings,
                     const RenderStats& stats, const Film& film);
// A film's resolved RGBA as an image, to compare with a reference.
ImageDesc film_image(const Film& film);

// 12.3k, 4.5M, 1.20G: counts for summaries.
std::string si(double v);

// The positive duration given to `option` (60, "30s", "2m", "1h30m"); throws UsageError naming it.
double duration_option(const std::string& option, const std::string& text);
// Throws a UsageError naming `option` unless `name` is one of allocation_names().
void check_allocation_name(const std::string& option, const std::string& name);
// The --progress style ("bar", "plain" or "none"); throws UsageError for anything else.
ProgressStyle progress_style_option(const std::string& text);

}  // namespace prism
