// Bench runs: one render's figures for `prism bench`, their text form, CSV rows, and medians over repetitions.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace prism {

// What one render of one scene measured (rays counted per kind; seconds of the render alone).
struct BenchRun {
  uint64_t triangles = 0;
  double bvh_seconds = 0;
  double render_seconds = 0;
  uint64_t samples = 0;  // camera paths
  uint64_t camera_rays = 0, extension_rays = 0, shadow_rays = 0;
  double peak_mb = 0;    // of the process that rendered it
  double rel_mse = -1;   // against the scene's reference; negative when none was given

  bool has_error() const { return rel_mse >= 0; }
  // 1 / (relMSE x render seconds): what equal-time error comparisons rank by (0 without an error
  // figure, infinite when the image equals its reference).
  double efficiency() const;

  double mpaths_per_second() const { return rate(samples); }
  double mrays_per_second() const { return rate(camera_rays + extension_rays + shadow_rays); }
  double camera_mrays_per_second() const { return rate(camera_rays); }
  double extension_mrays_per_second() const { return rate(extension_rays); }
  double shadow_mrays_per_second() const { return rate(shadow_rays); }

 private:
  double rate(uint64_t count) const;
};

// A run as one line of text (exact: integers and round-tripping doubles), for passing it from the
// process that rendered to the one that reports.
std::string to_text(const BenchRun& run);
// The run to_text wrote, or nullopt for any other text.
std::optional<BenchRun> bench_run_from_text(const std::string& text);

// The median of each figure over a scene's runs, and the spread of render seconds: what a noisy
// machine allows to be quoted (a lucky or unlucky run moves neither the median nor the other runs).
struct BenchSummary {
  int runs = 0;
  uint64_t triangles = 0;
  double bvh_seconds = 0, render_seconds = 0;
  double mpaths = 0, mrays = 0, camera_mrays = 0, extension_mrays = 0, shadow_mrays = 0;
  double peak_mb = 0;  // the largest of the runs
  double rel_mse = -1, efficiency = 0;  // medians, when every run was measured against a reference
  double render_seconds_min = 0, render_seconds_max = 0;
};
// Throws std::invalid_argument when `runs` is empty.
BenchSummary summarize(const std::vector<BenchRun>& runs);

// The median of `values` (the mean of the middle two for an even count); throws std::invalid_argument when empty.
double median(std::vector<double> values);

// CSV of every run: a header naming the settings' and the figures' columns, then one row per run
// (relmse and efficiency empty when no reference was given).
std::string bench_csv_header();
struct BenchSettingsText {
  int spp = 0;
  std::string resolution, sampler;
  int max_depth = 0, threads = 0;
  int split = 1;  // continuations per camera sample (RenderSettings::split)
};
std::string bench_csv_row(const std::string& scene, int repetition, const BenchRun& run, const BenchSettingsText& s);

}  // namespace prism
