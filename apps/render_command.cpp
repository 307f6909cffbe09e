#include "apps/render_command.h"

#include <fmt/core.h>
#include <tbb/global_control.h>

#include <filesystem>
#include <memory>
#include <stdexcept>

#include "apps/command_errors.h"
#include "apps/exit_codes.h"
#include "apps/progress_bar.h"
#include "core/camera.h"
#include "core/renderer.h"
#include "core/sampler_factory.h"
#include "core/scene.h"
#include "integrators/integrator_factory.h"
#include "io/atomic_file.h"
#include "io/duration_text.h"
#include "io/errors.h"
#include "io/exr_writer.h"
#include "io/png_writer.h"
#include "io/render_attributes.h"
#include "io/scene_source.h"
#include "materials/material_eval.h"

namespace prism {
namespace {

void parse_resolution(const std::string& text, int& width, int& height) {
  int w = 0, h = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') || w <= 0 || h <= 0 ||
      w > 65536 || h > 65536)
    throw UsageError("--res: expected WIDTHxHEIGHT with each between 1 and 65536, got '" + text + "'");
  width = w;
  height = h;
}

// Defaults, then the job file, then the command line.
RenderSettings resolve_settings(const RenderOptions& o, const std::optional<JobFile>& job) {
  RenderSettings s;
  if (job) job->settings.apply_to(s);
  RenderSettingsOverride cli = o.settings;
  if (o.resolution) {
    int w = 0, h = 0;
    parse_resolution(*o.resolution, w, h);
    cli.width = w;
    cli.height = h;
  }
  if (o.time) {
    const std::optional<double> seconds = parse_duration(*o.time);
    if (!seconds || !(*seconds > 0)) throw UsageError("--time: expected a duration such as 30s, 2m or 1h30m, got '" + *o.time + "'");
    cli.time_budget = *seconds;
  }
  cli.apply_to(s);
  // Under a budget, spp is only a ceiling: none with a time budget, a generous one for a noise target.
  const bool spp_given = o.settings.spp || (job && job->settings.spp);
  if (!spp_given && s.time_budget > 0) s.spp = s.noise_target > 0 ? 4096 : (1 << 30);
  else if (!spp_given && s.noise_target > 0) s.spp = 4096;
  if (s.spp < 1) throw UsageError("--spp must be at least 1");
  if (s.max_depth < 0) throw UsageError("--max-depth must be at least 0");
  if (s.threads < 0) throw UsageError("--threads must be at least 0 (0 = all cores)");
  return s;
}

std::string default_output(const std::string& scene) {
  return std::filesystem::path(scene).stem().string() + ".exr";
}

std::string si(double v) {
  if (v >= 1e9) return fmt::format("{:.2f}G", v / 1e9);
  if (v >= 1e6) return fmt::format("{:.1f}M", v / 1e6);
  if (v >= 1e3) return fmt::format("{:.1f}k", v / 1e3);
  return fmt::format("{:.0f}", v);
}

// --env takes a map's path, or one or three numbers for a constant sky.
EnvironmentSpec environment_option(const RenderOptions& o) {
  EnvironmentSpec spec;
  if (o.env) {
    float r, g, b;
    char extra;
    if (std::sscanf(o.env->c_str(), "%f,%f,%f%c", &r, &g, &b, &extra) == 3) spec.color = Rgb(r, g, b);
    else if (std::sscanf(o.env->c_str(), "%f%c", &r, &extra) == 1) spec.color = Rgb(r);
    else spec.map = *o.env;
    if (spec.color && !(min(*spec.color, Rgb(0.0f)) == Rgb(0.0f) && is_finite(*spec.color)))
      throw UsageError("--env: a constant sky needs finite non-negative numbers, got '" + *o.env + "'");
  }
  if (o.env_intensity) spec.intensity = *o.env_intensity;
  if (o.env_rotation) spec.rotation_degrees = *o.env_rotation;
  return spec;
}

// "64" for a uniform count; "16-1024 (mean 97.3)" when pixels differ.
std::string spp_summary(const RenderStats& stats) {
  if (stats.spp_min == stats.spp_max) return std::to_string(stats.spp_min);
  return fmt::format("{}-{} (mean {:.1f})", stats.spp_min, stats.spp_max, stats.spp_mean);
}

int render(const RenderOptions& o) {
  Diagnostics diag;
  LoadedScene loaded = load_scene_source(o.scene, diag, environment_option(o));
  if (!o.quiet)
    for (const auto& w : diag.lines()) fmt::print(stderr, "prism: warning: {}\n", w);

  RenderSettings settings = resolve_settings(o, loaded.job);
  const std::string output = o.output ? *o.output : (loaded.job && loaded.job->output ? *loaded.job->output : default_output(o.scene));
  std::optional<std::string> preview = o.preview;
  if (!preview && loaded.job && loaded.job->preview) preview = loaded.job->preview;
  check_output_path(output);
  if (preview) check_output_path(*preview);

  CameraDesc camera_desc;
  try {
    camera_desc = select_camera(loaded.scene, settings.camera);
  } catch (const std::invalid_argument& e) {
    throw InputError(o.scene, "camera", e.what());
  }
  if (settings.width == 0 || settings.height == 0) default_resolution(camera_desc, settings.width, settings.height);
  std::unique_ptr<Integrator> integrator;
  try {
    make_sampler(settings.sampler, 0);
    integrator = make_integrator(settings);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }

  std::optional<tbb::global_control> limit;
  if (settings.threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, size_t(settings.threads));

  std::unique_ptr<Scene> scene;
  try {
    scene = std::make_unique<Scene>(std::move(loaded.scene), &material_alpha);
  } catch (const std::invalid_argument& e) {
    throw InputError(o.scene, "", e.what());
  }
  if (scene->emitters().empty() && !o.quiet)
    fmt::print(stderr, "prism: warning: the scene has no lights (emitting surfaces or punctual lights), so its colour "
                       "channels render black (give one with --env; alpha still shows coverage)\n");
  const Camera camera(camera_desc, settings.width, settings.height);
  Film film(settings.width, settings.height);
  RenderProgress progress;
  RenderStats stats;
  {
    std::optional<ProgressBar> bar;
    if (!o.quiet) bar.emplace(progress.samples_done, progress.samples_total, "rendering");
    stats = prism::render(*scene, camera, *integrator, settings, film, &progress);
  }

  const std::vector<float> rgba = film.resolve_rgba();
  std::vector<ExrAttribute> attributes = render_attributes(settings, stats);
  attributes.push_back({"prism/version", std::string(PRISM_VERSION)});
  attributes.push_back({"prism/scene", o.scene});
  attributes.push_back({"prism/camera", camera_desc.name});
  if (scene->desc().environment.present) {
    attributes.push_back({"prism/environment", scene->desc().environment.source.empty()
                                                   ? std::string("constant")
                                                   : scene->desc().environment.source});
  }
  std::vector<ExrChannel> extra;
  if (stats.spp_min != stats.spp_max) extra.push_back({"spp", film.resolve_counts()});
  const int replaced = write_exr(output, settings.width, settings.height, rgba, attributes, extra);
  if (preview) write_png_preview(*preview, settings.width, settings.height, rgba);

  if (!o.quiet) {
    if (replaced > 0) fmt::print(stderr, "prism: warning: {} pixel values overflowed float and were clamped\n", replaced);
    const double secs = stats.seconds > 0 ? stats.seconds : 1e-9;
    fmt::print("{}x{}, {} spp, {:.2f} s, {:.2f} Mpaths/s, {:.2f} Mrays/s (camera {}, extension {}, shadow {}), "
               "BVH {:.3f} s, {} non-finite samples -> {}{}\n",
               settings.width, settings.height, spp_summary(stats), stats.seconds, double(stats.samples) / secs / 1e6,
               double(stats.rays.total()) / secs / 1e6, si(double(stats.rays.camera)), si(double(stats.rays.extension)),
               si(double(stats.rays.shadow)), scene->build_seconds(), stats.nonfinite_samples, output,
               preview ? " + " + *preview : "");
    if (settings.time_budget > 0 || settings.noise_target > 0)
      fmt::print("{} passes, estimated relative error {:.4f} (RMS over pixels){}\n", stats.passes, stats.relative_error,
                 settings.noise_target > 0
                     ? fmt::format(", {:.1f}% of pixels under the noise target {}", 100 * stats.converged_fraction,
                                   settings.noise_target)
                     : std::string());
  }
  return kExitOk;
}

}  // namespace

int run_render(const RenderOptions& options) {
  return run_reporting_errors([&] { return render(options); });
}

}  // namespace prism
