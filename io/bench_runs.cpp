#include "io/bench_runs.h"

#include <fmt/core.h>

#include <algorithm>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace prism {
namespace {

// A CSV field, quoted as RFC 4180 asks when it holds a comma, a quote or a line break.
std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + "\"";
}

constexpr const char* kTextTag = "prism-bench-run";

}  // namespace

double BenchRun::rate(uint64_t count) const { return double(count) / std::max(render_seconds, 1e-9) / 1e6; }

double BenchRun::efficiency() const {
  if (!has_error()) return 0.0;
  return rel_mse > 0 ? 1.0 / (rel_mse * std::max(render_seconds, 1e-9)) : std::numeric_limits<double>::infinity();
}

std::string to_text(const BenchRun& r) {
  return fmt::format("{} {} {:.17g} {:.17g} {} {} {} {} {:.17g} {:.17g}", kTextTag, r.triangles, r.bvh_seconds,
                     r.render_seconds, r.samples, r.camera_rays, r.extension_rays, r.shadow_rays, r.peak_mb, r.rel_mse);
}

std::optional<BenchRun> bench_run_from_text(const std::string& text) {
  std::istringstream in(text);
  std::string tag;
  BenchRun r;
  if (!(in >> tag) || tag != kTextTag) return std::nullopt;
  if (!(in >> r.triangles >> r.bvh_seconds >> r.render_seconds >> r.samples >> r.camera_rays >> r.extension_rays >>
        r.shadow_rays >> r.peak_mb >> r.rel_mse))
    return std::nullopt;
  std::string rest;
  if (in >> rest) return std::nullopt;
  return r;
}

double median(std::vector<double> values) {
  if (values.empty()) throw std::invalid_argument("median of no values");
  const size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + mid, values.end());
  if (values.size() % 2) return values[mid];
  const double upper = values[mid];
  const double lower = *std::max_element(values.begin(), values.begin() + mid);
  return 0.5 * (lower + upper);
}

BenchSummary summarize(const std::vector<BenchRun>& runs) {
  if (runs.empty()) throw std::invalid_argument("a bench summary of no runs");
  auto med = [&](auto figure) {
    std::vector<double> v;
    for (const BenchRun& r : runs) v.push_back(figure(r));
    return median(std::move(v));
  };
  BenchSummary s;
  s.runs = static_cast<int>(runs.size());
  s.triangles = runs.front().triangles;
  s.bvh_seconds = med([](const BenchRun& r) { return r.bvh_seconds; });
  s.render_seconds = med([](const BenchRun& r) { return r.render_seconds; });
  s.mpaths = med([](const BenchRun& r) { return r.mpaths_per_second(); });
  s.mrays = med([](const BenchRun& r) { return r.mrays_per_second(); });
  s.camera_mrays = med([](const BenchRun& r) { return r.camera_mrays_per_second(); });
  s.extension_mrays = med([](const BenchRun& r) { return r.extension_mrays_per_second(); });
  s.shadow_mrays = med([](const BenchRun& r) { return r.shadow_mrays_per_second(); });
  if (std::all_of(runs.begin(), runs.end(), [](const BenchRun& r) { return r.has_error(); })) {
    s.rel_mse = med([](const BenchRun& r) { return r.rel_mse; });
    s.efficiency = med([](const BenchRun& r) { return r.efficiency(); });
  }
  s.render_seconds_min = s.render_seconds_max = runs.front().render_seconds;
  for (const BenchRun& r : runs) {
    s.peak_mb = std::max(s.peak_mb, r.peak_mb);
    s.render_seconds_min = std::min(s.render_seconds_min, r.render_seconds);
    s.render_seconds_max = std::max(s.render_seconds_max, r.render_seconds);
  }
  return s;
}

std::string bench_csv_header() {
  return "scene,run,spp,resolution,max_depth,sampler,threads,split,triangles,bvh_s,render_s,mpaths_s,mrays_s,"
         "camera_mrays_s,extension_mrays_s,shadow_mrays_s,peak_mb,relmse,efficiency\n";
}

std::string bench_csv_row(const std::string& scene, int repetition, const BenchRun& r, const BenchSettingsText& s) {
  const std::string error = r.has_error() ? fmt::format("{:.8g},{:.8g}", r.rel_mse, r.efficiency()) : ",";
  return fmt::format("{},{},{},{},{},{},{},{},{},{:.6f},{:.6f},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.1f},{}\n",
                     csv_field(scene), repetition, s.spp, csv_field(s.resolution), s.max_depth, csv_field(s.sampler),
                     s.threads, s.split, r.triangles, r.bvh_seconds, r.render_seconds, r.mpaths_per_second(),
                     r.mrays_per_second(), r.camera_mrays_per_second(), r.extension_mrays_per_second(),
                     r.shadow_mrays_per_second(), r.peak_mb, error);
}

}  // namespace prism
