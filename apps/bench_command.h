// The `prism bench` command: renders the canonical scenes and prints one line of figures per scene.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace prism {

struct BenchOptions {
  std::vector<std::string> scenes;  // default: the canonical scenes of the source tree
  int spp = 16;
  std::string resolution = "512x512";
  int max_depth = 8;
  int threads = 0;
  std::string sampler = "sobol";
  int split = 1;    // continuations per camera sample (render --split)
  int repeat = 1;   // renders of each scene; the line gives their medians
  std::string csv;  // every run's figures, when set
  std::optional<std::string> references;  // folder of converged images: errors are measured when set
  int reference_spp = 1024;
};

CLI::App* add_bench_command(CLI::App& app, BenchOptions& options);

int run_bench(const BenchOptions& options);

}  // namespace prism
