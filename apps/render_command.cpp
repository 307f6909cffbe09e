#include "apps/render_command.h"

#include <fmt/core.h>
#include <tbb/global_control.h>

#include <filesystem>
#include <memory>

#include "apps/command_errors.h"
#include "apps/exit_codes.h"
#include "apps/progress_bar.h"
#include "apps/render_setup.h"
#include "core/camera.h"
#include "core/renderer.h"
#include "integrators/integrator_factory.h"
#include "io/atomic_file.h"
#include "io/exr_writer.h"
#include "io/film_state.h"
#include "io/png_writer.h"
#include "io/camera_attributes.h"
#include "io/render_attributes.h"
#include "io/render_layers.h"

namespace prism {
namespace {

std::string default_output(const std::string& scene) {
  return std::filesystem::path(scene).stem().string() + ".exr";
}

// "64" for a uniform count; "16-1024 (mean 97.3)" when pixels differ.
std::string spp_summary(const RenderStats& stats) {
  if (stats.spp_min == stats.spp_max) return std::to_string(stats.spp_min);
  return fmt::format("{}-{} (mean {:.1f})", stats.spp_min, stats.spp_max, stats.spp_mean);
}

int render(const RenderOptions& o) {
  PreparedRender p = prepare_render(o);
  const RenderSettings& settings = p.settings;
  const std::string output = o.output ? *o.output : (p.job && p.job->output ? *p.job->output : default_output(o.scene));
  std::optional<std::string> preview = o.preview;
  if (!preview && p.job && p.job->preview) preview = p.job->preview;
  check_output_path(output);
  if (preview) check_output_path(*preview);

  std::optional<tbb::global_control> limit;
  if (settings.threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, size_t(settings.threads));
  build_scene(p, o.quiet);
  const Scene& scene = *p.scene;
  const std::unique_ptr<Integrator> integrator = make_integrator(settings);
  const Camera camera(p.camera, settings.width, settings.height);
  const PixelWindow full{0, 0, settings.width, settings.height};
  const PixelWindow window = settings.crop.empty() ? full : settings.crop;
  Film film(window.width(), window.height(), settings.aovs);
  if (settings.aovs.has(Aov::CryptoObject) || settings.aovs.has(Aov::CryptoMaterial))
    film.set_cryptomatte_ids(object_cryptomatte_ids(scene.desc()), material_cryptomatte_ids(scene.desc()));
  RenderProgress progress;
  RenderStats stats;
  {
    std::optional<ProgressBar> bar;
    if (!o.quiet) bar.emplace(progress.samples_done, progress.samples_total, "rendering");
    stats = prism::render(scene, camera, *integrator, settings, film, &progress);
  }

  ExrImage image;
  image.display = full;
  image.data = window;
  image.attributes = render_attributes(settings, stats);
  for (ExrAttribute& a : camera_attributes(camera)) image.attributes.push_back(std::move(a));
  image.attributes.push_back({"prism/version", std::string(PRISM_VERSION)});
  image.attributes.push_back({"prism/scene", o.scene});
  image.attributes.push_back({"prism/camera", p.camera.name});
  if (scene.desc().environment.present) {
    image.attributes.push_back({"prism/environment", scene.desc().environment.source.empty()
                                                         ? std::string("constant")
                                                         : scene.desc().environment.source});
  }
  const std::optional<std::string> job_type = p.job ? p.job->pixel_type : std::nullopt;
  const std::string pixel_type = o.pixel_type ? *o.pixel_type : job_type.value_or("half");
  LayerOptions layers;
  layers.beauty = pixel_type == "float" ? ExrPixelType::Float : ExrPixelType::Half;
  add_render_layers(film, &scene.desc(), layers, image);
  // A sample slice is a part of a render: it carries its film exactly, for prism merge.
  if (!o.sample_range.empty() || (p.job && p.job->settings.first_sample)) add_film_state(film, image);
  const std::optional<std::string> job_compression = p.job ? p.job->compression : std::nullopt;
  image.compression = *parse_exr_compression(o.compression ? *o.compression : job_compression.value_or("zip"));
  image.multipart = o.multipart || (p.job && p.job->multipart.value_or(false));
  const ExrWriteReport written = write_exr(output, image);
  if (preview) write_png_preview(*preview, window.width(), window.height(), film.resolve_rgba());

  if (!o.quiet) {
    if (written.nonfinite > 0)
      fmt::print(stderr, "prism: warning: {}: {} pixel values overflowed float and were clamped\n", output, written.nonfinite);
    if (written.clamped > 0)
      fmt::print(stderr,
                 "prism: warning: {}: {} pixel values above 65504, the largest half, were clamped to it; "
                 "write float (--pixel-type float) to keep them\n",
                 output, written.clamped);
    const double secs = stats.seconds > 0 ? stats.seconds : 1e-9;
    fmt::print("{}x{}, {} spp, {:.2f} s, {:.2f} Mpaths/s, {:.2f} Mrays/s (camera {}, extension {}, shadow {}), "
               "BVH {:.3f} s, {} non-finite samples -> {}{}\n",
               settings.width, settings.height, spp_summary(stats), stats.seconds, double(stats.samples) / secs / 1e6,
               double(stats.rays.total()) / secs / 1e6, si(double(stats.rays.camera)), si(double(stats.rays.extension)),
               si(double(stats.rays.shadow)), scene.build_seconds(), stats.nonfinite_samples, output,
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
