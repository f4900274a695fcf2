#pragma once
// Line plots as PNG, drawn with OpenCV (no plotting library): stacked panels, each with its own
// y axis, several labelled series, and an optional vertical marker (e.g. the chosen F).
#include <optional>
#include <string>
#include <vector>

namespace aief::io {

struct PlotSeries {
  std::string label;
  std::vector<double> x, y;
};

struct PlotPanel {
  std::string y_label;
  std::vector<PlotSeries> series;
};

struct Plot {
  std::string title;
  std::string x_label;
  std::vector<PlotPanel> panels;
  std::optional<double> marker_x;  // a dashed vertical line across every panel
  std::string marker_label;
};

void write_plot_png(const std::string& path, const Plot& plot);

}  // namespace aief::io
