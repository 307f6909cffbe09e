#include "apps/compare_command.h"

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "apps/command_errors.h"
#include "apps/exit_codes.h"
#include "core/image_metrics.h"
#include "io/exr_writer.h"
#include "io/image_decode.h"
#include "io/png_writer.h"

namespace prism {
namespace {

double metric_value(const ImageComparison& c, const std::string& metric) {
  if (metric == "rmse") return c.rmse;
  if (metric == "relmse") return c.all.rel_mse;
  if (metric == "psnr") return c.psnr;
  if (metric == "maxabs") return c.all.max_abs;
  if (metric == "relerr") return c.relative_error_rms;
  throw UsageError("--metric: expected rmse, relmse, psnr, maxabs or relerr, got '" + metric + "'");
}

// A perceptually ordered dark-to-bright ramp (black, purple, red, orange, pale yellow), sRGB.
Rgb false_colour(float t) {
  static constexpr std::array<std::array<float, 3>, 5> stops = {{{0.00f, 0.00f, 0.02f},
                                                                 {0.34f, 0.06f, 0.43f},
                                                                 {0.73f, 0.21f, 0.33f},
                                                                 {0.98f, 0.55f, 0.04f},
                                                                 {0.99f, 1.00f, 0.64f}}};
  t = std::clamp(t, 0.0f, 1.0f) * float(stops.size() - 1);
  const int i = std::min(int(t), int(stops.size()) - 2);
  const float f = t - float(i);
  Rgb c;
  for (int k = 0; k < 3; ++k) {
    const float s = stops[i][k] * (1 - f) + stops[i + 1][k] * f;
    (&c.x)[k] = srgb_to_linear(s);  // the PNG writer encodes linear values
  }
  return c;
}

void write_difference(const CompareOptions& o, const ImageDesc& test, const ImageDesc& reference) {
  const std::vector<float> error = relative_error_map(test, reference);
  const size_t n = error.size();
  std::vector<float> rgba(n * 4, 1.0f);
  const bool exr = o.diff->ends_with(".exr");
  float scale = 1;
  if (!exr) {
    // Unless given, the 99th percentile maps to the top of the ramp, so a few outliers do not
    // flatten the rest.
    std::vector<float> sorted = error;
    std::nth_element(sorted.begin(), sorted.begin() + ptrdiff_t(n * 99 / 100), sorted.end());
    scale = o.diff_max ? *o.diff_max : std::max(sorted[n * 99 / 100], 1e-6f);
  }
  for (size_t i = 0; i < n; ++i) {
    const Rgb c = exr ? Rgb(error[i]) : false_colour(error[i] / scale);
    rgba[i * 4 + 0] = c.x;
    rgba[i * 4 + 1] = c.y;
    rgba[i * 4 + 2] = c.z;
  }
  if (exr) write_exr(*o.diff, test.width, test.height, rgba, {{"prism/difference", std::string("relative error")}});
  else write_png_preview(*o.diff, test.width, test.height, rgba);
  if (!o.quiet)
    fmt::print("difference image: {} ({}){}\n", *o.diff,
               exr ? "relative error per pixel" : "relative error, false colour",
               exr ? "" : fmt::format(", black 0 to pale yellow {:.4g}", scale));
}

int compare(const CompareOptions& o) {
  const ImageDesc test = read_image_file(o.test, ColorSpace::Auto),
                  reference = read_image_file(o.reference, ColorSpace::Auto);
  ImageComparison c;
  try {
    c = compare_images(test, reference);
  } catch (const std::invalid_argument& e) {
    throw UsageError(o.test + " vs " + o.reference + ": " + e.what());
  }
  const double value = metric_value(c, o.metric);
  if (!o.quiet) {
    fmt::print("{} vs reference {}: {}x{}, {} pixels compared\n", o.test, o.reference, test.width, test.height, c.pixels);
    fmt::print("{:<8}{:>14}{:>14}{:>14}{:>14}{:>14}\n", "channel", "mean", "mean ref", "RMSE", "relMSE", "max |diff|");
    const char* names[3] = {"R", "G", "B"};
    for (int k = 0; k < 3; ++k) {
      const ChannelError& e = c.channel[k];
      fmt::print("{:<8}{:>14.6g}{:>14.6g}{:>14.6g}{:>14.6g}{:>14.6g}\n", names[k], e.mean_test, e.mean_reference,
                 std::sqrt(e.mse), e.rel_mse, e.max_abs);
    }
    fmt::print("{:<8}{:>14.6g}{:>14.6g}{:>14.6g}{:>14.6g}{:>14.6g}\n", "RGB", c.all.mean_test, c.all.mean_reference,
               c.rmse, c.all.rel_mse, c.all.max_abs);
    fmt::print("PSNR {:.2f} dB (peak 1); non-finite pixels: {} in the image, {} in the reference\n", c.psnr,
               c.nonfinite_test, c.nonfinite_reference);
    fmt::print("relative error of the luminance per pixel (what --noise bounds): RMS {:.6g}, median {:.6g}\n",
               c.relative_error_rms, c.relative_error_median);
  }
  if (o.diff) write_difference(o, test, reference);
  if (o.threshold) {
    // PSNR is better when higher; the others when lower. Non-finite pixels always fail.
    const bool pass = (o.metric == "psnr" ? value >= *o.threshold : value <= *o.threshold) && c.nonfinite_test == 0;
    if (!o.quiet) fmt::print("{} {:.6g} {} threshold {:.6g}\n", o.metric, value, pass ? "within" : "MISSES", *o.threshold);
    return pass ? kExitOk : kExitThreshold;
  }
  return kExitOk;
}

}  // namespace

CLI::App* add_compare_command(CLI::App& app, CompareOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "compare", "Error metrics of an image against a reference: mean, RMSE, relative MSE, max difference, PSNR");
  cmd->add_option("IMAGE", o.test, "Image to measure (EXR, or any format OpenImageIO reads)")->required();
  cmd->add_option("REFERENCE", o.reference, "Reference image of the same size")->required();
  cmd->add_option("--metric", o.metric,
                  "Metric --threshold tests: relmse (default; mean of (a-b)^2/(b^2+0.01)), rmse, psnr (dB, peak 1), "
                  "maxabs, relerr (RMS over pixels of the luminance's |a-b|/max(b, 1% of the reference's mean): "
                  "what --noise bounds)");
  cmd->add_option("--threshold", o.threshold,
                  "Exit with status 5 when the metric is worse than this (PSNR below it; the others above it), or "
                  "when the image has non-finite pixels");
  cmd->add_option("--diff", o.diff,
                  "Write the per-pixel relative error: a false-colour PNG, or an EXR of the raw values (by extension)");
  cmd->add_option("--diff-max", o.diff_max, "Relative error at the top of the false-colour ramp (default: 99th percentile)")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("-q,--quiet", o.quiet, "Print nothing; only the exit status tells");
  return cmd;
}

int run_compare(const CompareOptions& options) {
  return run_reporting_errors([&] { return compare(options); });
}

}  // namespace prism
