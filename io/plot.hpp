#pragma once
// Line plots as PNG, drawn with OpenCV (no plotting library): stacked panels, each with its own
// y axis, several labelled series, and an optional vertical marker (e.g. the chosen F).
// Every series has its own colour and marker shape; ticks are round values (io/plot_axis.hpp);
// legends and the marker's label sit in the right margin, outside the data.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace aief::io {

struct PlotSeries {
  std::string label;
  std::vector<double> x, y;
};

struct PlotPanel {
  std::string y_label;  // with its unit, e.g. "matching accuracy (%)"
  std::vector<PlotSeries> series;
};

struct Plot {
  std::string title;
  std::string x_label;  // with its unit
  std::vector<PlotPanel> panels;
  std::optional<double>
      marker_x;  // a dashed vertical line across every panel, named in the first legend
  std::string marker_label;
};

enum class Marker { circle, square, triangle_up, diamond, triangle_down, cross, plus, ring };
struct SeriesStyle {
  unsigned char red, green, blue;
  Marker marker;
};
// The style of a panel's index-th series: no two of the first 40 share both colour and marker, and
// the first 8 share neither.
SeriesStyle series_style(std::size_t index);

void write_plot_png(const std::string& path, const Plot& plot);

}  // namespace aief::io
