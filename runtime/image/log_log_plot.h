// A small log-log scatter plot written as PNG (OpenImageIO drawing): what `lantern trade` draws
// for error against frame time. Points carry labels; an optional polyline marks a front (the
// Pareto front). Text uses the DejaVu Sans font (Debian fonts-dejavu-core); without it the plot
// is drawn without text and a warning is logged.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace lantern::runtime {

struct PlotPoint {
  double x = 0.0;  // > 0
  double y = 0.0;  // > 0
  std::string label;
  bool highlighted = false;  // drawn larger and filled (e.g. on the Pareto front)
};

struct LogLogPlot {
  std::string title;
  std::string x_label;
  std::string y_label;
  std::vector<PlotPoint> points;
  std::vector<std::pair<double, double>> line;  // polyline through (x, y), e.g. the front
};

// Writes the plot atomically; InputError when there is no positive finite point to draw,
// RuntimeError when the file cannot be written.
void write_log_log_plot(const std::filesystem::path& path, const LogLogPlot& plot,
                        int width = 900, int height = 600);

}  // namespace lantern::runtime
