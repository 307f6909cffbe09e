#include "apps/merge_command.h"

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <algorithm>
#include <map>
#include <optional>

#include "apps/command_errors.h"
#include "core/film.h"
#include "io/atomic_file.h"
#include "io/exr_reader.h"
#include "io/exr_writer.h"
#include "io/film_state.h"
#include "io/png_writer.h"
#include "io/render_identity.h"
#include "io/render_layers.h"

namespace prism {
namespace {

struct Part {
  std::string path;
  ExrImage image;
  uint64_t first_sample = 0;
};

uint64_t first_sample_of(const ExrImage& image, const std::string& path) {
  const ExrAttribute* a = image.attribute("prism/firstSample");
  const std::string* s = a ? std::get_if<std::string>(&a->second) : nullptr;
  if (!s) return 0;
  if (s->empty() || s->find_first_not_of("0123456789") != std::string::npos || s->size() > 19)
    throw InputError(path, "prism/firstSample", "'" + *s + "' is not a sample index");
  return std::stoull(*s);
}

int merge(const MergeOptions& o) {
  if (o.parts.empty()) throw UsageError("merge: give the partial renders to merge");
  check_output_path(o.output);
  if (o.preview) check_output_path(*o.preview);
  std::vector<Part> parts;
  for (const std::string& path : o.parts) parts.push_back({path, read_exr(path), 0});
  const ExrImage& first = parts.front().image;
  for (Part& p : parts) {
    p.first_sample = first_sample_of(p.image, p.path);
    // Parts of one render agree on everything but their slice and window.
    check_same_render(p.image, p.path, first, parts.front().path);
  }

  // Parts with the same data window are sample slices of it: their films add. Different windows
  // are crops: they must not overlap, and together must fill a rectangle.
  std::vector<std::pair<PixelWindow, Film>> windows;
  std::map<size_t, std::vector<std::pair<uint64_t, uint64_t>>> ranges;  // window -> sample ranges
  for (const Part& p : parts) {
    Film film = film_from_image(p.image, p.path);
    auto same = std::find_if(windows.begin(), windows.end(), [&](const auto& w) { return w.first == p.image.data; });
    const uint64_t count = film.sample_count(0, 0);
    if (same == windows.end()) {
      for (const auto& w : windows) {
        const PixelWindow& a = w.first;
        const PixelWindow& b = p.image.data;
        if (a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1)
          throw InputError(p.path, "dataWindow", "overlaps another part's window without being the same window");
      }
      ranges[windows.size()].push_back({p.first_sample, count});
      windows.emplace_back(p.image.data, std::move(film));
    } else {
      auto& r = ranges[size_t(same - windows.begin())];
      for (const auto& [start, n] : r)
        if (p.first_sample < start + n && start < p.first_sample + count)
          throw InputError(p.path, "prism/firstSample",
                           fmt::format("samples {}..{} overlap another part's: each slice must be rendered once",
                                       p.first_sample, p.first_sample + count - 1));
      r.push_back({p.first_sample, count});
      same->second.merge(film);
    }
  }
  PixelWindow bounds = windows.front().first;
  uint64_t covered = 0;
  for (const auto& [w, film] : windows) {
    bounds = {std::min(bounds.x0, w.x0), std::min(bounds.y0, w.y0), std::max(bounds.x1, w.x1), std::max(bounds.y1, w.y1)};
    covered += uint64_t(w.width()) * uint64_t(w.height());
  }
  if (covered != uint64_t(bounds.width()) * uint64_t(bounds.height()))
    throw InputError(o.parts.front(), "dataWindow",
                     fmt::format("the parts' windows leave pixels of {} {} {} {} uncovered", bounds.x0, bounds.y0, bounds.x1, bounds.y1));

  // Stitch the windows into one film.
  Film merged(bounds.width(), bounds.height(), windows.front().second.aovs());
  for (const auto& [w, film] : windows) merged.merge(film, w.x0 - bounds.x0, w.y0 - bounds.y0);

  ExrImage out;
  out.display = first.display;
  out.data = bounds;
  out.compression = first.compression;
  out.multipart = first.multipart;
  // The first part's header, less what described only that part; the Cryptomatte manifests come
  // with it, since every part renders the same scene.
  for (const ExrAttribute& a : first.attributes) {
    static const char* dropped[] = {"prism/firstSample", "prism/crop", "prism/spp", "prism/sppMin", "prism/sppMax",
                                    "prism/sppMean", "prism/relativeError", "prism/renderSeconds", "prism/passes",
                                    "capDate", "prism/status", "prism/farmTask"};
    if (std::find(std::begin(dropped), std::end(dropped), a.first) == std::end(dropped) && a.first.rfind("prism.state", 0) != 0)
      out.attributes.push_back(a);
  }
  const Film::SampleCounts counts = merged.sample_counts();
  const uint64_t lo = counts.min, hi = counts.max;
  out.attributes.push_back({"prism/spp", int(hi)});
  out.attributes.push_back({"prism/sppMin", int(lo)});
  out.attributes.push_back({"prism/sppMax", int(hi)});
  out.attributes.push_back({"prism/sppMean", double(counts.total) / (double(merged.width()) * merged.height())});
  // Complete only when every part is: a stopped or checkpointed part leaves the merge unfinished too.
  const bool complete = std::all_of(parts.begin(), parts.end(),
                                    [](const Part& p) { return attribute_text(p.image, "prism/status") == "complete"; });
  out.attributes.push_back({"prism/status", std::string(complete ? "complete" : "incomplete")});
  std::string sources;
  for (const Part& p : parts) sources += (sources.empty() ? "" : " ") + p.path;
  out.attributes.push_back({"prism/mergedFrom", fmt::format("{} parts: {}", parts.size(), sources)});
  for (const auto& extra : o.extra_attributes) {
    std::erase_if(out.attributes, [&](const ExrAttribute& a) { return a.first == extra.first; });
    out.attributes.push_back({extra.first, extra.second});
  }
  const ExrChannel* r = first.find("R");
  LayerOptions layers;
  layers.beauty = r && r->type == ExrPixelType::Float ? ExrPixelType::Float : ExrPixelType::Half;
  add_render_layers(merged, nullptr, layers, out);
  write_exr(o.output, out);
  if (o.preview) write_png_preview(*o.preview, merged.width(), merged.height(), merged.resolve_rgba());
  if (!o.quiet)
    fmt::print("merged {} parts ({} windows) -> {}: {}x{} at ({}, {}), {}-{} spp\n", parts.size(), windows.size(), o.output,
               bounds.width(), bounds.height(), bounds.x0, bounds.y0, lo, hi);
  return kExitOk;
}

}  // namespace

CLI::App* add_merge_command(CLI::App& app, MergeOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "merge", "Combine partial renders of one scene: sample slices (--sample-range) add by per-pixel sample count, "
               "crops (--crop) are stitched");
  cmd->add_option("PARTS", o.parts, "The partial renders (EXR files written by prism render)")->required();
  cmd->add_option("-o,--output", o.output, "The merged EXR")->required();
  cmd->add_option("--preview", o.preview, "Also write an 8-bit sRGB PNG preview of the merged image to this path");
  cmd->add_flag("-q,--quiet", o.quiet, "Print nothing but errors");
  return cmd;
}

int run_merge(const MergeOptions& options) {
  return run_reporting_errors([&] { return merge(options); });
}

}  // namespace prism
