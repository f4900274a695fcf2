#include "io/plot.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "aief/error.hpp"
#include "io/plot_axis.hpp"

namespace aief::io {

namespace {

constexpr int kWidth = 1000, kPanelHeight = 260, kLeft = 70, kRight = 280, kTop = 64, kGap = 64;
constexpr int kLegendRow = 20;

// Tableau 10 (RGB): ten hues told apart on white, also in print.
constexpr unsigned char kColours[][3] = {
    {31, 119, 180}, {255, 127, 14},  {44, 160, 44},   {214, 39, 40},  {148, 103, 189},
    {140, 86, 75},  {227, 119, 194}, {127, 127, 127}, {188, 189, 34}, {23, 190, 207}};
constexpr Marker kMarkers[] = {Marker::circle,  Marker::square,        Marker::triangle_up,
                               Marker::diamond, Marker::triangle_down, Marker::cross,
                               Marker::plus,    Marker::ring};

cv::Scalar bgr(const SeriesStyle& style) {
  return {double(style.blue), double(style.green), double(style.red)};
}

void text(cv::Mat& image, const std::string& s, cv::Point at, double scale = 0.45,
          cv::Scalar color = {0, 0, 0}) {
  cv::putText(image, s, at, cv::FONT_HERSHEY_SIMPLEX, scale, color, 1, cv::LINE_AA);
}

int text_width(const std::string& s, double scale) {
  int baseline = 0;
  return cv::getTextSize(s, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &baseline).width;
}

void draw_marker(cv::Mat& image, cv::Point c, const SeriesStyle& style, int r = 5) {
  const cv::Scalar colour = bgr(style);
  const auto polygon = [&](std::vector<cv::Point> points) {
    cv::fillConvexPoly(image, points, colour, cv::LINE_AA);
    cv::polylines(image, points, true, cv::Scalar::all(255), 1,
                  cv::LINE_AA);  // a white rim parts touching markers
  };
  switch (style.marker) {
    case Marker::circle:
      cv::circle(image, c, r, colour, cv::FILLED, cv::LINE_AA);
      cv::circle(image, c, r, cv::Scalar::all(255), 1, cv::LINE_AA);
      break;
    case Marker::square:
      polygon({{c.x - r + 1, c.y - r + 1},
               {c.x + r - 1, c.y - r + 1},
               {c.x + r - 1, c.y + r - 1},
               {c.x - r + 1, c.y + r - 1}});
      break;
    case Marker::triangle_up:
      polygon({{c.x, c.y - r - 1}, {c.x + r + 1, c.y + r - 1}, {c.x - r - 1, c.y + r - 1}});
      break;
    case Marker::diamond:
      polygon({{c.x, c.y - r - 1}, {c.x + r, c.y}, {c.x, c.y + r + 1}, {c.x - r, c.y}});
      break;
    case Marker::triangle_down:
      polygon({{c.x - r - 1, c.y - r + 1}, {c.x + r + 1, c.y - r + 1}, {c.x, c.y + r + 1}});
      break;
    case Marker::cross:
      cv::line(image, {c.x - r, c.y - r}, {c.x + r, c.y + r}, colour, 2, cv::LINE_AA);
      cv::line(image, {c.x - r, c.y + r}, {c.x + r, c.y - r}, colour, 2, cv::LINE_AA);
      break;
    case Marker::plus:
      cv::line(image, {c.x - r - 1, c.y}, {c.x + r + 1, c.y}, colour, 2, cv::LINE_AA);
      cv::line(image, {c.x, c.y - r - 1}, {c.x, c.y + r + 1}, colour, 2, cv::LINE_AA);
      break;
    case Marker::ring:
      cv::circle(image, c, r, cv::Scalar::all(255), cv::FILLED, cv::LINE_AA);
      cv::circle(image, c, r, colour, 2, cv::LINE_AA);
      break;
  }
}

void dashed_vertical(cv::Mat& image, int x, int top, int bottom) {
  for (int y = top; y < bottom; y += 8)
    cv::line(image, {x, y}, {x, std::min(y + 4, bottom)}, cv::Scalar::all(0), 1);
}

}  // namespace

SeriesStyle series_style(std::size_t index) {
  const auto& c = kColours[index % std::size(kColours)];
  return {c[0], c[1], c[2], kMarkers[index % std::size(kMarkers)]};
}

void write_plot_png(const std::string& path, const Plot& plot) {
  const int panels = std::max<int>(1, static_cast<int>(plot.panels.size()));
  const int height = kTop + panels * (kPanelHeight + kGap) + 10;
  cv::Mat image(height, kWidth, CV_8UC3, cv::Scalar::all(255));
  text(image, plot.title, {kLeft, 26}, 0.65);

  double x_min = std::numeric_limits<double>::max(), x_max = std::numeric_limits<double>::lowest();
  for (const PlotPanel& panel : plot.panels)
    for (const PlotSeries& s : panel.series)
      for (double x : s.x)
        if (std::isfinite(x)) x_min = std::min(x_min, x), x_max = std::max(x_max, x);
  if (plot.marker_x)
    x_min = std::min(x_min, *plot.marker_x), x_max = std::max(x_max, *plot.marker_x);
  if (x_min > x_max) x_min = 0, x_max = 1;
  // Small whole numbers (pair indices) are categories: one tick each, the axis ending at the data.
  const bool integer_axis = x_min == std::floor(x_min) && x_max == std::floor(x_max) &&
                            x_max > x_min && x_max - x_min <= 20;
  AxisTicks x_ticks;
  if (integer_axis) {
    x_ticks.step = 1;
    for (double x = x_min; x <= x_max; ++x) x_ticks.values.push_back(x);
  } else {
    x_ticks = round_ticks(x_min, x_max, 8);
  }
  const double x_lo = x_ticks.values.front(), x_hi = x_ticks.values.back();
  const int plot_w = kWidth - kLeft - kRight;
  // Categories get a margin of a quarter step either side, so the spread-out markers stay inside.
  const double pad = integer_axis ? 0.25 : 0;
  const auto px = [&](double x) {
    return kLeft +
           static_cast<int>(std::lround((x - x_lo + pad) / (x_hi - x_lo + 2 * pad) * plot_w));
  };
  const int legend_x = kLeft + plot_w + 14;

  for (int p = 0; p < static_cast<int>(plot.panels.size()); ++p) {
    const PlotPanel& panel = plot.panels[static_cast<std::size_t>(p)];
    const int top = kTop + p * (kPanelHeight + kGap), bottom = top + kPanelHeight;
    double y_min = 0, y_max = 0;  // the y axis starts at zero (counts and rates)
    for (const PlotSeries& s : panel.series)
      for (double y : s.y)
        if (std::isfinite(y)) y_max = std::max(y_max, y), y_min = std::min(y_min, y);
    const AxisTicks y_ticks = round_ticks(y_min, y_max, 5);
    const double y_lo = y_ticks.values.front(), y_hi = y_ticks.values.back();
    const auto py = [&](double y) {
      return bottom - static_cast<int>(std::lround((y - y_lo) / (y_hi - y_lo) * kPanelHeight));
    };

    for (double y : y_ticks.values) {
      cv::line(image, {kLeft, py(y)}, {kLeft + plot_w, py(y)}, cv::Scalar::all(228));
      const std::string label = y_ticks.label(y);
      text(image, label, {kLeft - 8 - text_width(label, 0.4), py(y) + 4}, 0.4);
    }
    for (double x : x_ticks.values) {
      cv::line(image, {px(x), bottom}, {px(x), bottom + 4}, cv::Scalar::all(120));
      const std::string label = x_ticks.label(x);
      text(image, label, {px(x) - text_width(label, 0.4) / 2, bottom + 18}, 0.4);
    }
    cv::rectangle(image, {kLeft, top}, {kLeft + plot_w, bottom}, cv::Scalar::all(120));
    text(image, panel.y_label, {kLeft, top - 12},
         0.45);  // clear of a marker sitting on the top edge
    if (p + 1 == static_cast<int>(plot.panels.size()))
      text(image, plot.x_label,
           {kLeft + (plot_w - text_width(plot.x_label, 0.45)) / 2, bottom + 40}, 0.45);

    // Series that coincide stay visible: every line is drawn before any marker; on a category axis
    // each series is moved sideways by a few pixels, elsewhere a series drawn earlier has wider
    // lines and larger markers, so one drawn over it leaves its edges showing.
    const std::size_t n = panel.series.size();
    const auto below = [&](std::size_t si) {
      return integer_axis ? 0 : static_cast<int>(std::min<std::size_t>(n - 1 - si, 2));
    };
    const auto dodge = [&](std::size_t si) {
      return integer_axis && n > 1
                 ? static_cast<int>(std::lround((static_cast<double>(si) - (n - 1) / 2.0) * 3))
                 : 0;
    };
    const auto point_of = [&](std::size_t si, std::size_t i) {
      return cv::Point(px(panel.series[si].x[i]) + dodge(si), py(panel.series[si].y[i]));
    };
    const auto drawn = [&](const PlotSeries& s, std::size_t i) {
      return std::isfinite(s.x[i]) && std::isfinite(s.y[i]);
    };
    for (std::size_t si = 0; si < n; ++si) {
      const PlotSeries& s = panel.series[si];
      for (std::size_t i = 1; i < std::min(s.x.size(), s.y.size()); ++i)
        if (drawn(s, i) && drawn(s, i - 1))
          cv::line(image, point_of(si, i - 1), point_of(si, i), bgr(series_style(si)),
                   2 + below(si), cv::LINE_AA);
    }
    if (plot.marker_x) dashed_vertical(image, px(*plot.marker_x), top, bottom);
    for (std::size_t si = 0; si < n; ++si) {
      const PlotSeries& s = panel.series[si];
      for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i)
        if (drawn(s, i)) draw_marker(image, point_of(si, i), series_style(si), 5 + below(si));
    }

    // The legend, in the right margin: line, marker and label per series, then the vertical marker.
    int row = top + 14;
    for (std::size_t si = 0; si < n; ++si, row += kLegendRow) {
      cv::line(image, {legend_x, row - 4}, {legend_x + 24, row - 4}, bgr(series_style(si)), 2,
               cv::LINE_AA);
      draw_marker(image, {legend_x + 12, row - 4}, series_style(si));
      text(image, panel.series[si].label, {legend_x + 32, row}, 0.42);
    }
    if (plot.marker_x && !plot.marker_label.empty()) {
      dashed_vertical(image, legend_x + 12, row - 12, row + 4);
      text(image, plot.marker_label, {legend_x + 32, row}, 0.42);
    }
  }
  bool ok = false;
  try {
    ok = cv::imwrite(path, image);
  } catch (const cv::Exception& e) {
    throw Error("cannot write plot '" + path + "': " + e.what());
  }
  if (!ok)
    throw Error("cannot write plot '" + path +
                "' (is the extension .png and the folder writable?)");
}

}  // namespace aief::io
