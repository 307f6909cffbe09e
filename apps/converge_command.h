// The `prism converge` command: error against time for each sampler and integrator, as CSV and a plot.
#pragma once

#include <optional>
#include <string>

#include "apps/render_command.h"

namespace CLI {
class App;
}

namespace prism {

struct ConvergeOptions {
  RenderOptions render;                  // scene, resolution, depth, seed, threads, camera
  std::optional<std::string> reference;  // rendered by prism at reference_spp when absent
  int reference_spp = 4096;
  std::string spp = "1,2,4,8,16,32,64,128,256";
  bool spp_given = false;  // --spp on the command line: its series is measured beside --times and --noise
  // Render-time budgets ("0.5s,1s,2s") and noise targets ("0.05,0.01") to measure at, each a series.
  std::optional<std::string> times, noise;
  std::string samplers = "sobol,independent";
  std::string integrators = "path";
  std::string allocations = "uniform";  // RenderSettings::allocation values to compare
  std::optional<std::string> rr_start_depths;  // a list to compare; the render default when absent
  std::optional<std::string> splits;           // path splits to compare; the render default (1) when absent
  std::string output_dir = ".";
};

CLI::App* add_converge_command(CLI::App& app, ConvergeOptions& options);

int run_converge(const ConvergeOptions& options);

}  // namespace prism
