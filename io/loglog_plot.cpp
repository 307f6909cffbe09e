#include "io/loglog_plot.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>

#include "io/atomic_file.h"
#include "io/errors.h"

namespace prism {
namespace {

constexpr double kWidth = 760, kHeight = 520;
constexpr double kLeft = 80, kRight = 230, kTop = 50, kBottom = 60;  // margins; the legend sits right
constexpr const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#17becf"};

std::string escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

// "1e-3", "0.01", "10": a tick label for 10^e.
std::string decade_label(int e) {
  if (e >= -2 && e <= 3) return fmt::format("{}", std::pow(10.0, e));
  return fmt::format("1e{}", e);
}

}  // namespace

double loglog_slope(const std::vector<std::pair<double, double>>& points) {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const auto& [x, y] : points) {
    if (!(x > 0 && y > 0)) continue;
    const double lx = std::log(x), ly = std::log(y);
    n += 1, sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
  }
  const double d = n * sxx - sx * sx;
  if (n < 2 || !(std::abs(d) > 0)) return std::numeric_limits<double>::quiet_NaN();
  return (n * sxy - sx * sy) / d;
}

void write_loglog_svg(const std::string& path, const LogLogPlot& plot) {
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = 0, y_lo = x_lo, y_hi = 0;
  for (const PlotSeries& s : plot.series)
    for (const auto& [x, y] : s.points) {
      if (!(x > 0 && y > 0) || !std::isfinite(x) || !std::isfinite(y)) continue;
      x_lo = std::min(x_lo, x), x_hi = std::max(x_hi, x), y_lo = std::min(y_lo, y), y_hi = std::max(y_hi, y);
    }
  if (!(x_hi > 0)) x_lo = 1, x_hi = 10, y_lo = 1, y_hi = 10;  // nothing to draw: an empty frame
  // Whole decades around the data.
  const int ex0 = int(std::floor(std::log10(x_lo))), ex1 = std::max(ex0 + 1, int(std::ceil(std::log10(x_hi))));
  const int ey0 = int(std::floor(std::log10(y_lo))), ey1 = std::max(ey0 + 1, int(std::ceil(std::log10(y_hi))));
  const double pw = kWidth - kLeft - kRight, ph = kHeight - kTop - kBottom;
  auto px = [&](double x) { return kLeft + (std::log10(x) - ex0) / (ex1 - ex0) * pw; };
  auto py = [&](double y) { return kTop + ph - (std::log10(y) - ey0) / (ey1 - ey0) * ph; };

  std::string svg = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}\" height=\"{}\" viewBox=\"0 0 {} {}\" "
      "font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n",
      kWidth, kHeight, kWidth, kHeight);
  svg += fmt::format("<text x=\"{}\" y=\"28\" font-size=\"15\" text-anchor=\"middle\">{}</text>\n", kLeft + pw / 2,
                     escape(plot.title));
  for (int e = ex0; e <= ex1; ++e) {
    const double x = px(std::pow(10.0, e));
    svg += fmt::format("<line x1=\"{0:.1f}\" y1=\"{1}\" x2=\"{0:.1f}\" y2=\"{2}\" stroke=\"#ddd\"/>\n", x, kTop, kTop + ph);
    svg += fmt::format("<text x=\"{:.1f}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n", x, kTop + ph + 18, decade_label(e));
  }
  for (int e = ey0; e <= ey1; ++e) {
    const double y = py(std::pow(10.0, e));
    svg += fmt::format("<line x1=\"{0}\" y1=\"{1:.1f}\" x2=\"{2}\" y2=\"{1:.1f}\" stroke=\"#ddd\"/>\n", kLeft, y, kLeft + pw);
    svg += fmt::format("<text x=\"{}\" y=\"{:.1f}\" text-anchor=\"end\">{}</text>\n", kLeft - 6, y + 4, decade_label(e));
  }
  svg += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"black\"/>\n", kLeft, kTop,
                     pw, ph);
  svg += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n", kLeft + pw / 2, kHeight - 18,
                     escape(plot.x_label));
  svg += fmt::format("<text transform=\"translate(20 {}) rotate(-90)\" text-anchor=\"middle\">{}</text>\n", kTop + ph / 2,
                     escape(plot.y_label));

  for (size_t i = 0; i < plot.series.size(); ++i) {
    const PlotSeries& s = plot.series[i];
    const char* colour = kColours[i % std::size(kColours)];
    std::string line;
    for (const auto& [x, y] : s.points) {
      if (!(x > 0 && y > 0) || !std::isfinite(x) || !std::isfinite(y)) continue;
      line += fmt::format("{:.1f},{:.1f} ", px(x), py(y));
      svg += fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"3\" fill=\"{}\"/>\n", px(x), py(y), colour);
    }
    svg += fmt::format("<polyline points=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"2\"/>\n", line, colour);
    const double slope = loglog_slope(s.points);
    const double ly = kTop + 10 + 20 * double(i);
    svg += fmt::format("<line x1=\"{0}\" y1=\"{1}\" x2=\"{2}\" y2=\"{1}\" stroke=\"{3}\" stroke-width=\"2\"/>\n",
                       kLeft + pw + 15, ly, kLeft + pw + 40, colour);
    svg += fmt::format("<text x=\"{}\" y=\"{}\">{} (slope {})</text>\n", kLeft + pw + 46, ly + 4, escape(s.name),
                       std::isfinite(slope) ? fmt::format("{:.2f}", slope) : std::string("n/a"));
  }
  svg += "</svg>\n";

  write_file_atomically(path, svg);
}

}  // namespace prism
