#include "apps/render_command.h"

#include <fmt/core.h>
#include <tbb/global_control.h>

#include <filesystem>
#include <memory>

#include "apps/command_errors.h"
#include "apps/exit_codes.h"
#include "apps/progress_bar.h"
#include "apps/render_setup.h"
#include "apps/stop_signals.h"
#include "core/camera.h"
#include "core/renderer.h"
#include "integrators/integrator_factory.h"
#include "io/atomic_file.h"
#include "io/exr_reader.h"
#include "io/exr_writer.h"
#include "io/film_state.h"
#include "io/png_writer.h"
#include "io/camera_attributes.h"
#include "io/render_attributes.h"
#include "io/render_identity.h"
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

// Everything in the header that describes the render rather than its pixels.
std::vector<ExrAttribute> header_attributes(const RenderOptions& o, const PreparedRender& p, const Camera& camera,
                                            const RenderStats& stats) {
  std::vector<ExrAttribute> a = render_attributes(p.settings, stats, o.stamp || (p.job && p.job->stamp.value_or(false)));
  for (ExrAttribute& c : camera_attributes(camera)) a.push_back(std::move(c));
  a.push_back({"prism/version", std::string(PRISM_VERSION)});
  a.push_back({"prism/scene", o.scene});
  a.push_back({"prism/camera", p.camera.name});
  const SceneDesc& desc = p.scene->desc();
  if (desc.environment.present)
    a.push_back({"prism/environment", desc.environment.source.empty() ? std::string("constant") : desc.environment.source});
  for (const auto& [name, value] : o.extra_attributes) a.push_back({name, value});
  return a;
}

// The film of a stopped render or checkpoint to continue: it must hold its exact state and have
// been rendered with the settings that decide the pixels.
Film resumed_film(const std::string& path, const ExrImage& expected) {
  const ExrImage image = read_exr(path);
  if (!has_film_state(image))
    throw InputError(path, "prism.state channels",
                     "missing: only renders that were stopped, checkpointed (--checkpoint) or resumed can be continued");
  check_same_render(image, path, expected, "this render");
  if (!(image.data == expected.data))
    throw InputError(path, "dataWindow", "differs from this render's crop: resume with the same --crop");
  for (const char* key : {"prism/firstSample", "prism/budget"})
    if (attribute_text(image, key) != attribute_text(expected, key))
      throw InputError(path, key, fmt::format("'{}' differs from this render's '{}'", attribute_text(image, key),
                                              attribute_text(expected, key)));
  return film_from_image(image, path);
}

int render(const RenderOptions& o, const BatchContext& batch) {
  PreparedRender p = prepare_render(o);
  RenderSettings& settings = p.settings;
  const std::string output = o.output ? *o.output : (p.job && p.job->output ? *p.job->output : default_output(o.scene));
  std::optional<std::string> preview = o.preview;
  if (!preview && p.job && p.job->preview) preview = p.job->preview;
  check_output_path(output);
  if (preview) check_output_path(*preview);
  std::optional<double> checkpoint = p.job ? p.job->checkpoint_seconds : std::nullopt;
  if (o.checkpoint) checkpoint = duration_option("--checkpoint", *o.checkpoint);
  const ProgressStyle progress_style =
      o.progress ? progress_style_option(*o.progress) : o.quiet ? ProgressStyle::None : ProgressStyle::Bar;
  // A fixed-spp render with checkpoints runs in passes of about the checkpoint period (same bits).
  if (checkpoint) settings.pass_seconds = *checkpoint;

  std::optional<tbb::global_control> limit;
  if (settings.threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, size_t(settings.threads));
  build_scene(p, o.quiet);
  const Scene& scene = *p.scene;
  const std::unique_ptr<Integrator> integrator = make_integrator(settings);
  const Camera camera(p.camera, settings.width, settings.height);
  const PixelWindow full{0, 0, settings.width, settings.height};
  const PixelWindow window = settings.crop.empty() ? full : settings.crop;
  const std::optional<std::string> job_type = p.job ? p.job->pixel_type : std::nullopt;
  const std::string pixel_type = o.pixel_type ? *o.pixel_type : job_type.value_or("half");
  const std::optional<std::string> job_compression = p.job ? p.job->compression : std::nullopt;
  // Renders that can be continued or merged carry their film exactly.
  const bool sliced = !o.sample_range.empty() || (p.job && p.job->settings.first_sample);
  const bool keep_state = sliced || checkpoint || o.resume;

  // The EXR of the film as it stands; `status` says whether the render is "complete", a
  // "checkpoint" of one in progress, or "stopped".
  auto image_of = [&](const Film& film, const RenderStats& stats, const std::string& status) {
    ExrImage image;
    image.display = full;
    image.data = window;
    image.attributes = header_attributes(o, p, camera, stats);
    image.attributes.push_back({"prism/status", status});
    LayerOptions layers;
    layers.beauty = pixel_type == "float" ? ExrPixelType::Float : ExrPixelType::Half;
    add_render_layers(film, &scene.desc(), layers, image);
    if (keep_state || status != "complete") add_film_state(film, image);
    image.compression = *parse_exr_compression(o.compression ? *o.compression : job_compression.value_or("zip"));
    image.multipart = o.multipart || (p.job && p.job->multipart.value_or(false));
    return image;
  };

  Film film(window.width(), window.height(), settings.aovs);
  if (o.resume) {
    ExrImage expected;  // the header this render writes, to check the file against
    expected.display = full;
    expected.data = window;
    expected.attributes = header_attributes(o, p, camera, RenderStats{});
    film = resumed_film(*o.resume, expected);
  }
  if (settings.aovs.has(Aov::CryptoObject) || settings.aovs.has(Aov::CryptoMaterial))
    film.set_cryptomatte_ids(object_cryptomatte_ids(scene.desc()), material_cryptomatte_ids(scene.desc()));
  const uint64_t resumed_samples = film.sample_counts().total;

  RenderProgress progress;
  RenderStats stats;
  {
    std::optional<StopSignals> signals;  // a batch has its own handler, which sets batch.stop
    if (batch.stop) progress.also_stop = batch.stop;
    else signals.emplace(progress.stop);
    std::optional<ProgressBar> bar;
    if (progress_style != ProgressStyle::None)
      bar.emplace(progress.samples_done, progress.samples_total, "rendering", progress_style, batch.position);
    double last_checkpoint = 0;
    PassObserver write_checkpoint;
    if (checkpoint)
      write_checkpoint = [&](const Film& f, const RenderStats& so_far) {
        // Passes last about one period; under a time or noise budget they grow, so write at most
        // about twice a period.
        if (so_far.seconds - last_checkpoint < 0.5 * *checkpoint) return;
        last_checkpoint = so_far.seconds;
        write_exr(output, image_of(f, so_far, "checkpoint"));
        if (preview) write_png_preview(*preview, window.width(), window.height(), f.resolve_rgba());
      };
    stats = prism::render(scene, camera, *integrator, settings, film, &progress, write_checkpoint);
  }

  const std::string status = stats.stopped ? "stopped" : "complete";
  const ExrWriteReport written = write_exr(output, image_of(film, stats, status));
  if (preview) write_png_preview(*preview, window.width(), window.height(), film.resolve_rgba());

  if (stats.stopped) {
    const int signal = batch.stop ? 0 : StopSignals::received();
    fmt::print(stderr,
               "prism: stopped{}{} after {} samples; {} holds every pixel's samples so far ({} spp); continue with "
               "--resume {}\n",
               signal ? " by " : "", signal ? StopSignals::name(signal) : "", si(double(resumed_samples + stats.samples)),
               output, spp_summary(stats), output);
    return kExitStopped;
  }
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
    if (settings.counts_follow_the_render())
      fmt::print("{} passes, estimated relative error {:.4f} (RMS over pixels){}\n", stats.passes, stats.relative_error,
                 settings.noise_target <= 0 ? std::string()
                 : settings.allocation == kUniformAllocation
                     ? fmt::format(", {:.1f}% of pixels under the noise target {}", 100 * stats.converged_fraction,
                                   settings.noise_target)
                     : fmt::format(", the whole image's noise target {} ({:.1f}% of pixels under it)",
                                   settings.noise_target, 100 * stats.converged_fraction));
    if (o.resume) fmt::print("continued {} with {} samples it already had\n", *o.resume, si(double(resumed_samples)));
  }
  return kExitOk;
}

}  // namespace

int run_render(const RenderOptions& options, const BatchContext& batch, std::string* message) {
  return run_reporting_errors([&] { return render(options, batch); }, message);
}

}  // namespace prism
