// Log-log line plots as SVG: error against time for convergence studies, drawn without a plotting library.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace prism {

struct PlotSeries {
  std::string name;
  std::vector<std::pair<double, double>> points;  // (x, y), both positive
};

struct LogLogPlot {
  std::string title, x_label, y_label;
  std::vector<PlotSeries> series;
};

// Least-squares slope of log y against log x (the convergence rate); NaN with fewer than two points.
double loglog_slope(const std::vector<std::pair<double, double>>& points);

// Writes the plot as a standalone SVG through a temporary file and a rename: decade grid lines,
// one coloured polyline with markers per series, and a legend giving each series' fitted slope.
// Non-positive points are left out. Throws OutputError naming the path on failure.
void write_loglog_svg(const std::string& path, const LogLogPlot& plot);

}  // namespace prism
