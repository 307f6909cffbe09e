#include "apps/bench_command.h"

#include <CLI/CLI.hpp>
#include <fmt/core.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <tbb/global_control.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "apps/command_errors.h"
#include "apps/render_setup.h"
#include "core/renderer.h"
#include "integrators/integrator_factory.h"

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

// Loads, builds and renders one scene; returns its line of figures (without the peak memory).
std::string bench_scene(const BenchOptions& o, const std::string& path) {
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
  const double secs = std::max(stats.seconds, 1e-9);
  auto mrays = [&](uint64_t n) { return double(n) / secs / 1e6; };
  return fmt::format("{:<22}{:>9}{:>8.3f}{:>9.2f}{:>9.2f}{:>9.2f}{:>9.2f}{:>9.2f}{:>9.2f}",
                     std::filesystem::path(path).filename().string().substr(0, 21),
                     si(double(p.scene->triangle_count())), p.scene->build_seconds(), stats.seconds,
                     double(stats.samples) / secs / 1e6, mrays(stats.rays.total()), mrays(stats.rays.camera),
                     mrays(stats.rays.extension), mrays(stats.rays.shadow));
}

// Each scene renders in a child process, so its peak memory is its own (wait4's ru_maxrss) and a
// failing scene cannot take the others down.
int bench(const BenchOptions& o) {
  const std::vector<std::string> scenes = o.scenes.empty() ? canonical_scenes() : o.scenes;
  fmt::print("prism {} bench: {} spp, {}, max depth {}, {} sampler, {} threads\n", PRISM_VERSION, o.spp, o.resolution,
             o.max_depth, o.sampler, o.threads > 0 ? std::to_string(o.threads) : "all");
  fmt::print("{:<22}{:>9}{:>8}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}\n", "scene", "tris", "BVH s", "render s", "Mpaths/s",
             "Mrays/s", "camera", "extend", "shadow", "peak MB");
  std::fflush(stdout);
  int failures = 0;
  for (const std::string& path : scenes) {
    int fds[2];
    if (::pipe(fds) != 0) throw std::runtime_error("pipe failed");
    const pid_t child = ::fork();
    if (child < 0) throw std::runtime_error("fork failed");
    if (child == 0) {
      ::close(fds[0]);
      int code = kExitOk;
      std::string line;
      code = run_reporting_errors([&] {
        line = bench_scene(o, path);
        return kExitOk;
      });
      if (::write(fds[1], line.data(), line.size()) < 0) code = kExitInternal;
      ::close(fds[1]);
      std::fflush(nullptr);
      ::_exit(code);
    }
    ::close(fds[1]);
    std::string line;
    char buffer[512];
    for (ssize_t n; (n = ::read(fds[0], buffer, sizeof buffer)) != 0;) {
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) break;
      line.append(buffer, size_t(n));
    }
    ::close(fds[0]);
    int status = 0;
    rusage usage{};
    while (::wait4(child, &status, 0, &usage) < 0 && errno == EINTR) {
    }
    const bool ok = WIFEXITED(status) && WEXITSTATUS(status) == 0 && !line.empty();
    if (ok) fmt::print("{}{:>9.0f}\n", line, double(usage.ru_maxrss) / 1024.0);  // ru_maxrss is in KiB on Linux
    else fmt::print("{:<22} failed (see the error above)\n", std::filesystem::path(path).filename().string());
    std::fflush(stdout);
    failures += !ok;
  }
  return failures ? kExitInput : kExitOk;
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
  return cmd;
}

int run_bench(const BenchOptions& options) {
  return run_reporting_errors([&] { return bench(options); });
}

}  // namespace prism
