#include "apps/render_setup.h"

#include <fmt/core.h>

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "apps/command_errors.h"
#include "core/hash.h"
#include "core/mip_levels.h"
#include "core/sample_schedule.h"
#include "core/sampler_factory.h"
#include "integrators/integrator_factory.h"
#include "io/duration_text.h"
#include "io/errors.h"
#include "io/exr_writer.h"
#include "io/render_attributes.h"
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
  if (o.time) cli.time_budget = duration_option("--time", *o.time);
  if (o.aovs) {
    try {
      cli.aovs = parse_aovs(*o.aovs);
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--aovs: ") + e.what());
    }
  }
  if (!o.crop.empty()) cli.crop = PixelWindow{o.crop[0], o.crop[1], o.crop[2], o.crop[3]};
  if (!o.sample_range.empty()) {
    if (o.settings.spp) throw UsageError("--sample-range gives the sample count: use it or --spp, not both");
    if (o.sample_range[1] < 1 || o.sample_range[1] > (1u << 30))
      throw UsageError("--sample-range: COUNT must be between 1 and 2^30");
    cli.first_sample = o.sample_range[0];
    cli.spp = int(o.sample_range[1]);
  }
  cli.apply_to(s);
  const bool sliced = !o.sample_range.empty() || (job && job->settings.first_sample);
  if (sliced && s.counts_follow_the_render())
    throw UsageError(
        "a sample range renders a fixed slice of samples: it cannot be combined with --time, --noise or --allocation "
        "error");
  check_allocation_name("--allocation", s.allocation);
  if (s.texture_filter != "trilinear" && s.texture_filter != "bilinear")
    throw UsageError("--texture-filter: unknown filter '" + s.texture_filter + "' (expected trilinear or bilinear)");
  // Under a budget, spp is only a ceiling: none with a time budget, a generous one for a noise target.
  const bool spp_given = o.settings.spp || (job && job->settings.spp);
  if (!spp_given && s.time_budget > 0) s.spp = s.noise_target > 0 ? 4096 : (1 << 30);
  else if (!spp_given && s.noise_target > 0) s.spp = 4096;
  if (s.spp < 1) throw UsageError("--spp must be at least 1");
  if (s.max_depth < 0) throw UsageError("--max-depth must be at least 0");
  if (s.threads < 0) throw UsageError("--threads must be at least 0 (0 = all cores)");
  return s;
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

}  // namespace

std::string si(double v) {
  if (v >= 1e9) return fmt::format("{:.2f}G", v / 1e9);
  if (v >= 1e6) return fmt::format("{:.1f}M", v / 1e6);
  if (v >= 1e3) return fmt::format("{:.1f}k", v / 1e3);
  return fmt::format("{:.0f}", v);
}

double duration_option(const std::string& option, const std::string& text) {
  const std::optional<double> seconds = parse_duration(text);
  if (!seconds || !(*seconds > 0))
    throw UsageError(option + ": expected a duration such as 60, 30s, 2m or 1h30m, got '" + text + "'");
  return *seconds;
}

void check_allocation_name(const std::string& option, const std::string& name) {
  const std::vector<std::string> names = allocation_names();
  if (std::find(names.begin(), names.end(), name) != names.end()) return;
  std::string known;
  for (size_t i = 0; i < names.size(); ++i) known += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
  throw UsageError(option + ": expected " + known + ", got '" + name + "'");
}

ProgressStyle progress_style_option(const std::string& text) {
  const std::optional<ProgressStyle> style = parse_progress_style(text);
  if (!style) throw UsageError("--progress: expected bar, plain or none, got '" + text + "'");
  return *style;
}

RenderOptions job_render_options(JobFile job, const std::string& list_file, const std::string& where) {
  RenderOptions render;
  render.scene = job.scene ? *job.scene : list_file + "#" + where;
  render.job = std::move(job);
  return render;
}

PreparedRender prepare_render(const RenderOptions& o) {
  Diagnostics diag;
  diag.strict = o.strict;
  LoadedScene loaded = o.job ? load_job(*o.job, diag, environment_option(o))
                             : load_scene_source(o.scene, diag, environment_option(o));
  if (!o.quiet)
    for (const auto& w : diag.lines()) fmt::print(stderr, "prism: warning: {}\n", w);

  PreparedRender p;
  p.scene_path = o.scene;
  p.settings = resolve_settings(o, loaded.job);
  p.job = std::move(loaded.job);
  try {
    p.camera = select_camera(loaded.scene, p.settings.camera);
  } catch (const std::invalid_argument& e) {
    throw InputError(o.scene, "camera", e.what());
  }
  if (p.settings.width == 0 || p.settings.height == 0) default_resolution(p.camera, p.settings.width, p.settings.height);
  const PixelWindow& crop = p.settings.crop;
  if (crop != PixelWindow{} && (crop.empty() || !PixelWindow{0, 0, p.settings.width, p.settings.height}.contains(crop)))
    throw UsageError(fmt::format("--crop {} {} {} {}: expected 0 <= x0 < x1 <= {} and 0 <= y0 < y1 <= {} (the image size)",
                                 crop.x0, crop.y0, crop.x1, crop.y1, p.settings.width, p.settings.height));
  try {
    make_sampler(p.settings.sampler, 0);
    make_integrator(p.settings);
    light_sampling(p.settings.light_sampler);  // build_scene builds the emitters for it
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  p.desc = std::move(loaded.scene);
  return p;
}

void build_scene(PreparedRender& p, bool quiet) {
  if (p.settings.texture_filter == "trilinear") build_texture_mips(p.desc, p.scene_path);
  try {
    p.scene = std::make_unique<Scene>(std::move(p.desc), &material_alpha, light_sampling(p.settings.light_sampler));
  } catch (const std::invalid_argument& e) {
    throw InputError(p.scene_path, "", e.what());
  }
  if (p.scene->emitters().empty() && !quiet)
    fmt::print(stderr, "prism: warning: the scene has no lights (emitting surfaces or punctual lights), so its colour "
                       "channels render black (give one with --env; alpha still shows coverage)\n");
}

RenderSettings reference_settings(RenderSettings settings, int spp) {
  settings.spp = spp;
  settings.seed = hash_values(settings.seed, 0x5eedull);
  return settings;
}

void write_reference(const std::string& path, const PreparedRender& render, const RenderSettings& settings,
                     const RenderStats& stats, const Film& film) {
  std::vector<ExrAttribute> attributes = render_attributes(settings, stats);
  attributes.push_back({"prism/scene", render.scene_path});
  write_exr(path, settings.width, settings.height, film.resolve_rgba(), attributes);
}

ImageDesc film_image(const Film& film) {
  ImageDesc img;
  img.width = film.width();
  img.height = film.height();
  img.channels = 4;
  img.texels = film.resolve_rgba();
  return img;
}

}  // namespace prism
