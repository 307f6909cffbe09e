#include "apps/bench_command.h"

#include <CLI/CLI.hpp>
#include <fmt/core.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <utility>

#include "apps/command_errors.h"
#include "apps/render_setup.h"
#include "core/hash.h"
#include "core/image_metrics.h"
#include "core/renderer.h"
#include "integrators/integrator_factory.h"
#include "io/atomic_file.h"
#include "io/bench_runs.h"
#include "io/image_decode.h"

namespace prism {
namespace {

// The canonical scenes, from the source tree prism was built from; the generated ones (too large
// for git) only once generated (scripts/bench does it).
std::vector<std::string> canonical_scenes() {
  const std::filesystem::path root = PRISM_SOURCE_DIR;
  std::vector<std::string> scenes = {(root / "scenes/cornell-box/cornell-box.gltf").string(),
                                     (root / "scenes/cornell-glass/cornell-glass.json").string(),
                                     (root / "scenes/many-lights/many-lights.gltf").string(),
                                     (root / "scenes/window-room/window-room.json").string()};
  struct Generated {
    const char* scene;                    // what bench renders
    std::vector<const char*> generated;  // what generate.py writes beside it
  };
  const Generated generated[] = {{"scenes/heavy-mesh/heavy-mesh.glb", {"heavy-mesh.glb"}},
                                 {"scenes/hdri-textures/hdri-textures.json", {"hdri-textures.glb", "sky.hdr"}}};
  for (const Generated& g : generated) {
    const std::filesystem::path scene = root / g.scene;
    bool present = true;
    for (const char* file : g.generated) present = present && std::filesystem::exists(scene.parent_path() / file);
    if (present) {
      scenes.push_back(scene.string());
      continue;
    }
    fmt::print(stderr, "prism: note: {} is not generated yet; generate it with {} (scripts/bench does)\n",
               scene.string(), (scene.parent_path() / "generate.py").string());
  }
  return scenes;
}

// Loads and builds `path` with the bench's settings, limits the worker threads as --threads asks,
// and hands the prepared render to `use` (the limit holds while it runs).
template <typename Use>
auto with_bench_scene(const BenchOptions& o, const std::string& path, Use use) {
  RenderOptions ro;
  ro.scene = path;
  ro.resolution = o.resolution;
  ro.settings.spp = o.spp;
  ro.settings.max_depth = o.max_depth;
  ro.settings.threads = o.threads;
  ro.settings.sampler = o.sampler;
  ro.settings.split = o.split;
  ro.quiet = true;
  PreparedRender p = prepare_render(ro);
  std::optional<tbb::global_control> limit;
  if (o.threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, size_t(o.threads));
  build_scene(p, true);
  return use(p);
}

// Renders `settings` on a prepared scene into a new film.
std::pair<Film, RenderStats> render_film(const PreparedRender& p, const RenderSettings& settings) {
  Film film(settings.width, settings.height);
  const RenderStats stats =
      render(*p.scene, Camera(p.camera, settings.width, settings.height), *make_integrator(settings), settings, film);
  return {std::move(film), stats};
}

// Loads, builds and renders one scene (in a process of its own, see run_in_child); the figures of
// that render, with its error against `reference` when one is named, measured after the clock
// stops and after the process's peak memory is read (reading an image must not count).
BenchRun bench_scene(const BenchOptions& o, const std::string& path, const std::string& reference) {
  return with_bench_scene(o, path, [&](const PreparedRender& p) {
    const RenderSettings& s = p.settings;
    const auto [film, stats] = render_film(p, s);
    BenchRun run;
    rusage usage{};
    if (::getrusage(RUSAGE_SELF, &usage) == 0) run.peak_mb = double(usage.ru_maxrss) / 1024.0;  // KiB on Linux
    if (!reference.empty()) {
      const ImageDesc ref = read_image_file(reference, ColorSpace::Linear);
      if (ref.width != s.width || ref.height != s.height)
        throw InputError(reference, "image size",
                         fmt::format("the reference is {}x{}, the bench renders {}x{}; delete it to render it again",
                                     ref.width, ref.height, s.width, s.height));
      run.rel_mse = compare_images(film_image(film), ref).all.rel_mse;
    }
    run.triangles = p.scene->triangle_count();
    run.bvh_seconds = p.scene->build_seconds();
    run.render_seconds = stats.seconds;
    run.samples = stats.samples;
    run.camera_rays = stats.rays.camera;
    run.extension_rays = stats.rays.extension;
    run.shadow_rays = stats.rays.shadow;
    return run;
  });
}

// Renders the converged image a scene's error is measured against, at --reference-spp with the
// Sobol sampler and paths unsplit (the same reference for every --sampler and --split) and another
// seed than the timed renders, so their errors are independent.
void render_reference(const BenchOptions& o, const std::string& path, const std::string& reference) {
  with_bench_scene(o, path, [&](const PreparedRender& p) {
    RenderSettings rs = reference_settings(p.settings, o.reference_spp);
    rs.sampler = "sobol";
    rs.split = 1;
    const auto [film, stats] = render_film(p, rs);
    write_reference(reference, p, rs, stats, film);
  });
}

// Runs `work` in a child process, so a render's peak memory is its own and a failing scene cannot
// take the others down. The child's text (what `work` returns), or nullopt when it failed (the
// child printed why).
template <typename Work>
std::optional<std::string> run_in_child(Work work) {
  int fds[2];
  if (::pipe(fds) != 0) throw std::runtime_error("pipe failed");
  std::fflush(nullptr);  // the child must not print the parent's buffered output again
  const pid_t child = ::fork();
  if (child < 0) throw std::runtime_error("fork failed");
  if (child == 0) {
    ::close(fds[0]);
    std::string text;
    int code = run_reporting_errors([&] {
      text = work();
      return kExitOk;
    });
    if (::write(fds[1], text.data(), text.size()) < 0) code = kExitInternal;
    ::close(fds[1]);
    std::fflush(nullptr);
    ::_exit(code);
  }
  ::close(fds[1]);
  std::string text;
  char buffer[512];
  for (ssize_t n; (n = ::read(fds[0], buffer, sizeof buffer)) != 0;) {
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) break;
    text.append(buffer, size_t(n));
  }
  ::close(fds[0]);
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) return std::nullopt;
  return text;
}

std::optional<BenchRun> bench_scene_in_child(const BenchOptions& o, const std::string& path,
                                             const std::string& reference) {
  const std::optional<std::string> out = run_in_child([&] { return to_text(bench_scene(o, path, reference)); });
  return out ? bench_run_from_text(*out) : std::nullopt;
}

// The processor's name as /proc/cpuinfo gives it, for the record of where figures were measured.
std::string processor_name() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("model name", 0) != 0) continue;
    const size_t colon = line.find(':');
    if (colon != std::string::npos) return line.substr(line.find_first_not_of(" \t", colon + 1));
  }
  return "unknown processor";
}

std::string scene_name(const std::string& path) { return std::filesystem::path(path).filename().string(); }

// Where a scene's reference lives in the --references folder: named by the scene (its file name
// and a hash of its absolute path, so scenes of one name in two folders do not collide) and by
// what the image depends on. A change to what the renderer converges to makes it stale: delete it.
std::string reference_path(const BenchOptions& o, const std::string& scene) {
  const std::filesystem::path path = std::filesystem::absolute(scene).lexically_normal();
  uint64_t h = 0;  // the same on every build, unlike std::hash
  for (const unsigned char c : path.string()) h = hash_combine(h, c);
  return (std::filesystem::path(*o.references) / fmt::format("{}-{:08x}-{}-d{}-{}spp.exr", path.stem().string(),
                                                              uint32_t(h), o.resolution, o.max_depth, o.reference_spp))
      .string();
}

// With --repeat, the scenes take turns (every scene once, then again), so a drift in the machine's
// speed during the call reaches every scene alike; each line then gives the medians of its runs.
int bench(const BenchOptions& o) {
  const std::vector<std::string> scenes = o.scenes.empty() ? canonical_scenes() : o.scenes;
  if (!o.csv.empty()) check_output_path(o.csv);
  if (o.references && !std::filesystem::is_directory(*o.references))
    throw OutputError(*o.references, "the references folder does not exist");
  const int threads = o.threads > 0 ? o.threads : tbb::this_task_arena::max_concurrency();
  std::vector<bool> failed(scenes.size(), false);
  std::vector<std::string> references(scenes.size());
  if (o.references) {
    for (size_t i = 0; i < scenes.size(); ++i) {
      references[i] = reference_path(o, scenes[i]);
      if (std::filesystem::exists(references[i])) continue;
      fmt::print("rendering the reference of {}: {} spp -> {}\n", scene_name(scenes[i]), o.reference_spp,
                 references[i]);
      std::fflush(stdout);
      failed[i] = !run_in_child([&] {
        render_reference(o, scenes[i], references[i]);
        return std::string();
      });
    }
  }
  const bool errors = o.references.has_value();
  fmt::print("prism {} bench: {} spp{}, {}, max depth {}, {} sampler, {} threads on {}{}\n", PRISM_VERSION, o.spp,
             o.split > 1 ? fmt::format(" (paths split in {} past the first vertex)", o.split) : "", o.resolution,
             o.max_depth, o.sampler, threads, processor_name(),
             o.repeat > 1 ? fmt::format("; medians of {} runs, scenes in turn", o.repeat) : "");
  fmt::print("{:<22}{:>9}{:>8}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{}{}\n", "scene", "tris", "BVH s", "render s", "Mpaths/s",
             "Mrays/s", "camera", "extend", "shadow", "peak MB",
             errors ? fmt::format("{:>12}{:>12}", "relMSE", "efficiency") : "",
             o.repeat > 1 ? "  render s min..max" : "");
  std::fflush(stdout);
  const BenchSettingsText settings{o.spp, o.resolution, o.sampler, o.max_depth, threads, o.split};
  std::vector<std::vector<BenchRun>> runs(scenes.size());
  std::string csv = bench_csv_header();
  auto print_line = [&](size_t i) {
    if (failed[i]) {
      fmt::print("{:<22} failed (see the error above)\n", scene_name(scenes[i]));
    } else {
      const BenchSummary m = summarize(runs[i]);
      fmt::print("{:<22}{:>9}{:>8.3f}{:>9.2f}{:>9.2f}{:>9.2f}{:>9.2f}{:>9.2f}{:>9.2f}{:>9.0f}{}{}\n",
                 scene_name(scenes[i]).substr(0, 21), si(double(m.triangles)), m.bvh_seconds, m.render_seconds, m.mpaths,
                 m.mrays, m.camera_mrays, m.extension_mrays, m.shadow_mrays, m.peak_mb,
                 errors ? fmt::format("{:>12.4g}{:>12.4g}", m.rel_mse, m.efficiency) : "",
                 o.repeat > 1 ? fmt::format("  {:.2f}..{:.2f}", m.render_seconds_min, m.render_seconds_max) : "");
    }
    std::fflush(stdout);
  };
  for (int rep = 1; rep <= o.repeat; ++rep) {
    if (o.repeat > 1 && ::isatty(STDERR_FILENO)) fmt::print(stderr, "prism: run {} of {}\n", rep, o.repeat);
    for (size_t i = 0; i < scenes.size(); ++i) {
      if (failed[i]) {
        if (rep == 1 && o.repeat == 1) print_line(i);  // its reference failed
        continue;
      }
      const std::optional<BenchRun> run = bench_scene_in_child(o, scenes[i], references[i]);
      if (run) {
        runs[i].push_back(*run);
        csv += bench_csv_row(scene_name(scenes[i]), rep, *run, settings);
      }
      failed[i] = !run;
      if (o.repeat == 1) print_line(i);  // at once: no more runs are to come
    }
  }
  if (o.repeat > 1)
    for (size_t i = 0; i < scenes.size(); ++i) print_line(i);  // a scene that failed once is reported failed
  if (!o.csv.empty()) {
    write_file_atomically(o.csv, csv);
    fmt::print("-> {}\n", o.csv);
  }
  return std::find(failed.begin(), failed.end(), true) != failed.end() ? kExitInput : kExitOk;
}

}  // namespace

CLI::App* add_bench_command(CLI::App& app, BenchOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "bench", "Render the canonical scenes and print, per scene: triangles, BVH build and render seconds, Mpaths/s, "
               "Mrays/s (all, camera, extension, shadow), peak memory and, with --references, relative MSE and efficiency");
  cmd->add_option("SCENES", o.scenes,
                  "Scenes to measure (default: scenes/cornell-box, scenes/cornell-glass, scenes/many-lights, "
                  "scenes/window-room and, once generated, scenes/heavy-mesh and scenes/hdri-textures)");
  cmd->add_option("--spp", o.spp, "Samples per pixel (default 16)")->check(CLI::PositiveNumber);
  cmd->add_option("--res", o.resolution, "Image size WIDTHxHEIGHT (default 512x512)");
  cmd->add_option("--max-depth", o.max_depth, "Maximum bounces (default 8)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--threads", o.threads, "Worker threads; 0 = all cores (default)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--sampler", o.sampler, "Sampler (default sobol)");
  cmd->add_option("--split", o.split, "Continuations per camera sample past its first vertex, as render --split (default 1)")
      ->check(CLI::Range(1, kMaxSplit));
  cmd->add_option("--repeat", o.repeat,
                  "Render each scene this many times, the scenes taking turns, and print the median of each figure "
                  "and the range of render seconds (default 1)")
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--csv", o.csv, "Also write every run's figures and settings to this CSV file");
  cmd->add_option("--references", o.references,
                  "Folder of converged images to measure each render's relative MSE and efficiency (1 / (relMSE x "
                  "seconds)) against; a scene's reference is rendered into it at --reference-spp when absent");
  cmd->add_option("--reference-spp", o.reference_spp, "Samples per pixel of the references bench renders (default 1024)")
      ->check(CLI::PositiveNumber);
  return cmd;
}

int run_bench(const BenchOptions& options) {
  return run_reporting_errors([&] { return bench(options); });
}

}  // namespace prism
