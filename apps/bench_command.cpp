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

#include "apps/command_errors.h"
#include "apps/render_setup.h"
#include "core/renderer.h"
#include "integrators/integrator_factory.h"
#include "io/atomic_file.h"
#include "io/bench_runs.h"

namespace prism {
namespace {

// The canonical scenes, from the source tree prism was built from; the heavy mesh only once
// generated (scripts/bench does it).
std::vector<std::string> canonical_scenes() {
  const std::filesystem::path root = PRISM_SOURCE_DIR;
  std::vector<std::string> scenes = {(root / "scenes/cornell-box/cornell-box.gltf").string(),
                                     (root / "scenes/cornell-glass/cornell-glass.json").string(),
                                     (root / "scenes/many-lights/many-lights.gltf").string()};
  const std::filesystem::path heavy = root / "scenes/heavy-mesh/heavy-mesh.glb";
  if (std::filesystem::exists(heavy)) scenes.push_back(heavy.string());
  else
    fmt::print(stderr, "prism: note: {} is absent; generate it with scenes/heavy-mesh/generate.py (scripts/bench does)\n",
               heavy.string());
  return scenes;
}

// Loads, builds and renders one scene; the figures of that render (without the peak memory).
BenchRun bench_scene(const BenchOptions& o, const std::string& path) {
  RenderOptions ro;
  ro.scene = path;
  ro.resolution = o.resolution;
  ro.settings.spp = o.spp;
  ro.settings.max_depth = o.max_depth;
  ro.settings.threads = o.threads;
  ro.settings.sampler = o.sampler;
  ro.quiet = true;
  PreparedRender p = prepare_render(ro);
  std::optional<tbb::global_control> limit;
  if (o.threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, size_t(o.threads));
  build_scene(p, true);
  const RenderSettings& s = p.settings;
  Film film(s.width, s.height);
  const RenderStats stats = render(*p.scene, Camera(p.camera, s.width, s.height), *make_integrator(s), s, film);
  BenchRun run;
  run.triangles = p.scene->triangle_count();
  run.bvh_seconds = p.scene->build_seconds();
  run.render_seconds = stats.seconds;
  run.samples = stats.samples;
  run.camera_rays = stats.rays.camera;
  run.extension_rays = stats.rays.extension;
  run.shadow_rays = stats.rays.shadow;
  return run;
}

// Renders one scene in a child process, so its peak memory is its own (wait4's ru_maxrss) and a
// failing scene cannot take the others down; nullopt when it failed (the child printed why).
std::optional<BenchRun> bench_scene_in_child(const BenchOptions& o, const std::string& path) {
  int fds[2];
  if (::pipe(fds) != 0) throw std::runtime_error("pipe failed");
  std::fflush(nullptr);  // the child must not print the parent's buffered output again
  const pid_t child = ::fork();
  if (child < 0) throw std::runtime_error("fork failed");
  if (child == 0) {
    ::close(fds[0]);
    std::string text;
    int code = run_reporting_errors([&] {
      text = to_text(bench_scene(o, path));
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
  rusage usage{};
  while (::wait4(child, &status, 0, &usage) < 0 && errno == EINTR) {
  }
  std::optional<BenchRun> run = bench_run_from_text(text);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || !run) return std::nullopt;
  run->peak_mb = double(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
  return run;
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

// With --repeat, the scenes take turns (every scene once, then again), so a drift in the machine's
// speed during the call reaches every scene alike; each line then gives the medians of its runs.
int bench(const BenchOptions& o) {
  const std::vector<std::string> scenes = o.scenes.empty() ? canonical_scenes() : o.scenes;
  if (!o.csv.empty()) check_output_path(o.csv);
  const int threads = o.threads > 0 ? o.threads : tbb::this_task_arena::max_concurrency();
  fmt::print("prism {} bench: {} spp, {}, max depth {}, {} sampler, {} threads on {}{}\n", PRISM_VERSION, o.spp,
             o.resolution, o.max_depth, o.sampler, threads, processor_name(),
             o.repeat > 1 ? fmt::format("; medians of {} runs, scenes in turn", o.repeat) : "");
  fmt::print("{:<22}{:>9}{:>8}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{}\n", "scene", "tris", "BVH s", "render s", "Mpaths/s",
             "Mrays/s", "camera", "extend", "shadow", "peak MB", o.repeat > 1 ? "  render s min..max" : "");
  std::fflush(stdout);
  const BenchSettingsText settings{o.spp, o.resolution, o.sampler, o.max_depth, threads};
  std::vector<std::vector<BenchRun>> runs(scenes.size());
  std::vector<bool> failed(scenes.size(), false);
  std::string csv = bench_csv_header();
  auto print_line = [&](size_t i) {
    if (failed[i]) {
      fmt::print("{:<22} failed (see the error above)\n", scene_name(scenes[i]));
    } else {
      const BenchSummary m = summarize(runs[i]);
      fmt::print("{:<22}{:>9}{:>8.3f}{:>9.2f}{:>9.2f}{:>9.2f}{:>9.2f}{:>9.2f}{:>9.2f}{:>9.0f}{}\n",
                 scene_name(scenes[i]).substr(0, 21), si(double(m.triangles)), m.bvh_seconds, m.render_seconds, m.mpaths,
                 m.mrays, m.camera_mrays, m.extension_mrays, m.shadow_mrays, m.peak_mb,
                 o.repeat > 1 ? fmt::format("  {:.2f}..{:.2f}", m.render_seconds_min, m.render_seconds_max) : "");
    }
    std::fflush(stdout);
  };
  for (int rep = 1; rep <= o.repeat; ++rep) {
    if (o.repeat > 1 && ::isatty(STDERR_FILENO)) fmt::print(stderr, "prism: run {} of {}\n", rep, o.repeat);
    for (size_t i = 0; i < scenes.size(); ++i) {
      if (failed[i]) continue;
      const std::optional<BenchRun> run = bench_scene_in_child(o, scenes[i]);
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
               "Mrays/s (all, camera, extension, shadow) and peak memory");
  cmd->add_option("SCENES", o.scenes,
                  "Scenes to measure (default: scenes/cornell-box, scenes/cornell-glass, scenes/many-lights and, once generated, "
                  "scenes/heavy-mesh)");
  cmd->add_option("--spp", o.spp, "Samples per pixel (default 16)")->check(CLI::PositiveNumber);
  cmd->add_option("--res", o.resolution, "Image size WIDTHxHEIGHT (default 512x512)");
  cmd->add_option("--max-depth", o.max_depth, "Maximum bounces (default 8)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--threads", o.threads, "Worker threads; 0 = all cores (default)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--sampler", o.sampler, "Sampler (default sobol)");
  cmd->add_option("--repeat", o.repeat,
                  "Render each scene this many times, the scenes taking turns, and print the median of each figure "
                  "and the range of render seconds (default 1)")
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--csv", o.csv, "Also write every run's figures and settings to this CSV file");
  return cmd;
}

int run_bench(const BenchOptions& options) {
  return run_reporting_errors([&] { return bench(options); });
}

}  // namespace prism
