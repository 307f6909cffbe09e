#include "apps/converge_command.h"

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "apps/command_errors.h"
#include "apps/render_setup.h"
#include "core/image_metrics.h"
#include "core/renderer.h"
#include "integrators/integrator_factory.h"
#include "io/atomic_file.h"
#include "io/image_decode.h"
#include "io/loglog_plot.h"

namespace prism {
namespace {

std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

// The items of a comma-separated list, each read by `parse` (which throws a UsageError naming the
// option), sorted by `order`, each once.
template <typename T, typename Parse, typename Order = std::less<>>
std::vector<T> parsed_list(const std::string& text, const std::string& option, Parse parse, Order order = {}) {
  std::vector<T> out;
  for (const std::string& item : split_list(text)) out.push_back(parse(item));
  if (out.empty()) throw UsageError(option + ": the list is empty");
  std::sort(out.begin(), out.end(), order);
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// One setting compared: the render's settings with some knobs changed, and its series' name.
struct Variant {
  RenderSettings settings;
  std::string name;
};

// Each of `variants` once for each of `values` of the knob, named "<name>/<prefix><value>" when
// `named`.
template <typename T>
void cross(std::vector<Variant>& variants, const std::vector<T>& values, T RenderSettings::*knob,
           const std::string& prefix, bool named) {
  std::vector<Variant> out;
  for (const Variant& v : variants)
    for (const T& value : values) {
      Variant w = v;
      w.settings.*knob = value;
      if (named) w.name += (w.name.empty() ? "" : "/") + prefix + fmt::format("{}", value);
      out.push_back(std::move(w));
    }
  variants = std::move(out);
}

// A comma-separated list of positive counts, smallest first; `example` shows the form in errors.
std::vector<int> count_list(const std::string& text, const std::string& option, const std::string& example) {
  return parsed_list<int>(text, option, [&](const std::string& item) {
    char* end = nullptr;
    const long v = std::strtol(item.c_str(), &end, 10);
    if (*end != '\0' || v < 1 || v > (1 << 30))
      throw UsageError(option + ": expected a list of counts such as " + example + ", got '" + text + "'");
    return int(v);
  });
}

// A comma-separated list of render-time budgets in seconds, shortest first.
std::vector<double> duration_list(const std::string& text) {
  return parsed_list<double>(text, "--times", [](const std::string& item) { return duration_option("--times", item); });
}

// A comma-separated list of relative-error targets in (0, 1], loosest first.
std::vector<double> noise_list(const std::string& text) {
  return parsed_list<double>(
      text, "--noise",
      [&](const std::string& item) {
        char* end = nullptr;
        const double v = std::strtod(item.c_str(), &end);
        if (*end != '\0' || !(v > 0 && v <= 1))
          throw UsageError("--noise: expected a list of relative errors such as 0.05,0.02,0.01, got '" + text + "'");
        return v;
      },
      std::greater<>());
}

// The most samples a pixel may take under a --times budget (the budget, not this, ends the
// render) and under a --noise target (as `prism render --noise` allows by default).
constexpr int kTimedSppCeiling = 1 << 24;
constexpr int kNoiseSppCeiling = 4096;

// How a series spends its samples: one film through fixed counts, a render per time budget, or
// a render per noise target (adaptive sampling).
enum class Budget { Spp, Time, Noise };

// What a series' name ends with when several kinds of budget are compared.
const char* budget_suffix(Budget kind) {
  switch (kind) {
    case Budget::Spp: return "/spp";
    case Budget::Time: return "/time";
    default: return "/noise";
  }
}

struct Row {
  std::string setting;
  double spp;  // the mean over the pixels: a time budget leaves some pixels one pass ahead
  double seconds;
  ImageComparison error;
};

int converge(const ConvergeOptions& o) {
  // Sample counts (one film carried through them), time budgets and noise targets (a render of
  // its own each): a series of each kind asked for, sample counts alone when nothing is.
  const std::vector<double> budgets = o.times ? duration_list(*o.times) : std::vector<double>{};
  const std::vector<double> targets = o.noise ? noise_list(*o.noise) : std::vector<double>{};
  const bool by_spp = o.spp_given || (!o.times && !o.noise);
  const std::vector<int> spps = by_spp ? count_list(o.spp, "--spp", "1,4,16,64") : std::vector<int>{};
  std::vector<Budget> kinds;
  if (by_spp) kinds.push_back(Budget::Spp);
  if (o.times) kinds.push_back(Budget::Time);
  if (o.noise) kinds.push_back(Budget::Noise);
  // Russian roulette's start is compared besides sampler and integrator: it trades noise for time
  // without bias, so only a measurement can choose it (docs/PERFORMANCE.md).
  std::vector<int> rr_starts;  // empty: the render's own
  if (o.rr_start_depths) rr_starts = count_list(*o.rr_start_depths, "--rr-start-depths", "3,4,5");
  // So is path splitting: it buys less noise per camera sample with more time per camera sample.
  std::vector<int> splits;  // empty: the render's own
  if (o.splits) splits = count_list(*o.splits, "--splits", "1,2,4");
  const std::vector<std::string> samplers = split_list(o.samplers), integrators = split_list(o.integrators);
  const std::vector<std::string> allocations = split_list(o.allocations);
  if (allocations.empty()) throw UsageError("--allocations needs at least one name");
  for (const std::string& a : allocations) check_allocation_name("--allocations", a);
  if (samplers.empty() || integrators.empty()) throw UsageError("--samplers and --integrators need at least one name");
  if (!std::filesystem::is_directory(o.output_dir))
    throw OutputError(o.output_dir, "the output folder does not exist");
  const std::filesystem::path dir(o.output_dir);
  const std::string csv_path = (dir / "convergence.csv").string(), svg_path = (dir / "convergence.svg").string();
  check_output_path(csv_path);
  check_output_path(svg_path);

  // A given reference fixes the resolution unless --res says otherwise (then sizes must agree).
  RenderOptions ro = o.render;
  std::optional<ImageDesc> reference;
  if (o.reference) {
    reference = read_image_file(*o.reference, ColorSpace::Linear);
    if (!ro.resolution) ro.resolution = fmt::format("{}x{}", reference->width, reference->height);
  }
  PreparedRender p = prepare_render(ro);
  if (rr_starts.empty()) rr_starts.push_back(p.settings.rr_start_depth);
  if (splits.empty()) splits.push_back(p.settings.split);
  build_scene(p, ro.quiet);
  // Every combination of the compared knobs, outermost first; integrator and sampler always name
  // a series, the other knobs only when more than one value of theirs is compared.
  std::vector<Variant> variants{{p.settings, ""}};
  cross(variants, integrators, &RenderSettings::integrator, "", true);
  cross(variants, samplers, &RenderSettings::sampler, "", true);
  cross(variants, rr_starts, &RenderSettings::rr_start_depth, "rr", rr_starts.size() > 1);
  cross(variants, splits, &RenderSettings::split, "split", splits.size() > 1);
  cross(variants, allocations, &RenderSettings::allocation, "", allocations.size() > 1);
  const Camera camera(p.camera, p.settings.width, p.settings.height);
  if (reference && (reference->width != p.settings.width || reference->height != p.settings.height))
    throw UsageError(fmt::format("--reference {} is {}x{} but the render is {}x{}", *o.reference, reference->width,
                                 reference->height, p.settings.width, p.settings.height));

  if (!reference) {
    // prism's own converged image, with another seed than the series so their errors are independent.
    const RenderSettings rs = reference_settings(p.settings, o.reference_spp);
    const std::string ref_path = (dir / "reference.exr").string();
    if (!ro.quiet) fmt::print("rendering the reference: {} spp, {} sampler -> {}\n", rs.spp, rs.sampler, ref_path);
    Film film(rs.width, rs.height);
    const RenderStats stats = render(*p.scene, camera, *make_integrator(rs), rs, film);
    write_reference(ref_path, p, rs, stats, film);
    reference = film_image(film);
  }

  std::vector<Row> rows;
  LogLogPlot plot{fmt::format("{}: relative MSE against render time ({}x{})",
                              std::filesystem::path(p.scene_path).filename().string(), p.settings.width,
                              p.settings.height),
                  "render time (s)", "relMSE", {}};
  if (!ro.quiet)
    fmt::print("{:<24}{:>8}{:>12}{:>12}{:>12}{:>14}{:>12}\n", "setting", "spp", "seconds", "RMSE", "relMSE",
               "efficiency", "rel. error");
  for (const Variant& variant : variants) {
    RenderSettings s = variant.settings;
    std::unique_ptr<Integrator> integrator;
    try {
      integrator = make_integrator(s);
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
    {
      // Warm up (thread pool, sampler validation) on one pixel so the first level's time is the render's.
      RenderSettings warm = s;
      warm.spp = 1;
      Film pixel(1, 1);
      try {
        render(*p.scene, camera, *integrator, warm, pixel);
      } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
      }
    }
    const std::string& base = variant.name;
    for (const Budget kind : kinds) {
      PlotSeries series{base + (kinds.size() == 1 ? "" : budget_suffix(kind)), {}};
      auto measured = [&](double spp, double seconds, const Film& film) {
        Row row{series.name, spp, seconds, compare_images(film_image(film), *reference)};
        const double efficiency = 1.0 / (row.error.all.rel_mse * seconds);
        if (!ro.quiet)
          fmt::print("{:<24}{:>8.6g}{:>12.3f}{:>12.5g}{:>12.5g}{:>14.5g}{:>12.5g}\n", row.setting, spp, seconds,
                     row.error.rmse, row.error.all.rel_mse, efficiency, row.error.relative_error_rms);
        series.points.emplace_back(seconds, row.error.all.rel_mse);
        rows.push_back(row);
      };
      // A render of its own under `budgeted`'s time budget or noise target: what a user who
      // asks `prism render` for that budget gets.
      auto render_budgeted = [&](const RenderSettings& budgeted) {
        Film film(s.width, s.height);
        const RenderStats stats = render(*p.scene, camera, *integrator, budgeted, film);
        measured(stats.spp_mean, stats.seconds, film);
      };
      if (kind == Budget::Spp) {
        Film film(s.width, s.height);
        double seconds = 0;
        // Sample counts are prefixes of one sequence: each level continues the previous film.
        for (int spp : spps) {
          s.spp = spp;
          seconds += render(*p.scene, camera, *integrator, s, film).seconds;
          measured(spp, seconds, film);
        }
      } else if (kind == Budget::Time) {
        for (double budget : budgets) {
          RenderSettings timed = s;
          timed.time_budget = budget;
          timed.spp = kTimedSppCeiling;
          render_budgeted(timed);
        }
      } else {
        for (double target : targets) {
          RenderSettings adaptive = s;
          adaptive.noise_target = target;
          adaptive.spp = kNoiseSppCeiling;
          render_budgeted(adaptive);
        }
      }
      plot.series.push_back(std::move(series));
    }
  }

  // relerr (last, so that readers of the older columns keep their places): the RMS relative error of
  // the luminance per pixel, what --noise bounds.
  std::string csv = "setting,spp,seconds,rmse,relmse,efficiency,relerr\n";
  for (const Row& r : rows)
    csv += fmt::format("{},{:.8g},{:.6f},{:.8g},{:.8g},{:.8g},{:.8g}\n", r.setting, r.spp, r.seconds, r.error.rmse,
                       r.error.all.rel_mse, 1.0 / (r.error.all.rel_mse * r.seconds), r.error.relative_error_rms);
  write_file_atomically(csv_path, csv);
  write_loglog_svg(svg_path, plot);
  if (!ro.quiet) {
    fmt::print("fitted slopes of log relMSE against log time (Monte Carlo: -1):");
    for (const PlotSeries& s : plot.series) {
      const double slope = loglog_slope(s.points);  // NaN for a series of one point, as the plot says
      fmt::print(" {} {};", s.name, std::isfinite(slope) ? fmt::format("{:.2f}", slope) : std::string("n/a"));
    }
    fmt::print("\n-> {}, {}\n", csv_path, svg_path);
  }
  return kExitOk;
}

}  // namespace

CLI::App* add_converge_command(CLI::App& app, ConvergeOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "converge", "Measure error against render time for samplers and integrators: a CSV and a log-log plot (SVG)");
  cmd->add_option("SCENE", o.render.scene, "Scene: a glTF file or a job file")->required();
  cmd->add_option("--reference", o.reference,
                  "Converged reference image (default: prism renders one at --reference-spp into the output folder)");
  cmd->add_option("--reference-spp", o.reference_spp, "Samples per pixel of the reference prism renders (default 4096)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--spp", o.spp,
                  "Sample counts to measure at, a comma-separated list (default 1,2,4,...,256; measured when "
                  "given, or when neither --times nor --noise is)")
      ->each([&o](const std::string&) { o.spp_given = true; });
  cmd->add_option("--times", o.times,
                  "Render-time budgets to measure at too, a comma-separated list such as 0.5s,1s,2s: each a render "
                  "of its own under that budget, as --time makes it (spp in the CSV is then the mean reached)");
  cmd->add_option("--noise", o.noise,
                  "Noise targets to measure at too, a comma-separated list such as 0.05,0.02,0.01: each a render "
                  "of its own with adaptive sampling, as --noise makes it (at most 4096 spp)");
  cmd->add_option("--allocations", o.allocations,
                  "How samples are shared among pixels, comma-separated to compare (uniform, error; default uniform; "
                  "series are named .../uniform and .../error when there are several)");
  cmd->add_option("--samplers", o.samplers, "Samplers to compare, comma-separated (default sobol,independent)");
  cmd->add_option("--integrators", o.integrators, "Integrators to compare, comma-separated (default path)");
  cmd->add_option("--res", o.render.resolution, "Image size WIDTHxHEIGHT (default: the reference's, else as render)");
  cmd->add_option("--max-depth", o.render.settings.max_depth, "Maximum bounces (default 8)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--rr-start-depths", o.rr_start_depths,
                  "Bounces from which Russian roulette starts, a comma-separated list to compare (default 4; series "
                  "are named INTEGRATOR/SAMPLER/rrN when there are several)");
  cmd->add_option("--splits", o.splits,
                  "Path splits to compare (continuations per camera sample past its first vertex, as render --split), "
                  "a comma-separated list such as 1,2,4 (default 1; series are named .../splitK when there are several)");
  cmd->add_option("--camera", o.render.settings.camera, "Camera by name or index (default: the first)");
  cmd->add_option("--seed", o.render.settings.seed, "Random seed of the series (default 0)");
  cmd->add_option("--threads", o.render.settings.threads, "Worker threads; 0 = all cores")->check(CLI::NonNegativeNumber);
  cmd->add_option("-o,--output-dir", o.output_dir,
                  "Folder for convergence.csv, convergence.svg and reference.exr (default: the current folder)");
  cmd->add_flag("-q,--quiet", o.render.quiet, "Print nothing but errors");
  return cmd;
}

int run_converge(const ConvergeOptions& options) {
  return run_reporting_errors([&] { return converge(options); });
}

}  // namespace prism
