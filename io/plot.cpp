#include "io/plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "aief/error.hpp"

namespace aief::io {

namespace {

constexpr int kWidth = 960, kPanelHeight = 260, kLeft = 70, kRight = 250, kTop = 64, kGap = 56;

const cv::Scalar kPalette[] = {{200, 90, 30}, {40, 160, 40}, {30, 30, 220}, {180, 60, 180}, {0, 150, 200}, {120, 120, 0}, {90, 90, 90}};

std::string number(double v) {
  char buffer[32];
  if (std::abs(v) >= 100 || v == std::floor(v)) std::snprintf(buffer, sizeof buffer, "%.0f", v);
  else std::snprintf(buffer, sizeof buffer, "%.2f", v);
  return buffer;
}

void text(cv::Mat& image, const std::string& s, cv::Point at, double scale = 0.45, cv::Scalar color = {0, 0, 0}) {
  cv::putText(image, s, at, cv::FONT_HERSHEY_SIMPLEX, scale, color, 1, cv::LINE_AA);
}

}  // namespace

void write_plot_png(const std::string& path, const Plot& plot) {
  const int panels = std::max<int>(1, static_cast<int>(plot.panels.size()));
  const int height = kTop + panels * (kPanelHeight + kGap) + 10;
  cv::Mat image(height, kWidth, CV_8UC3, cv::Scalar::all(255));
  text(image, plot.title, {kLeft, 26}, 0.65);

  double x_min = std::numeric_limits<double>::max(), x_max = std::numeric_limits<double>::lowest();
  for (const PlotPanel& panel : plot.panels)
    for (const PlotSeries& s : panel.series)
      for (double x : s.x) {
        x_min = std::min(x_min, x);
        x_max = std::max(x_max, x);
      }
  if (!(x_min < x_max)) {
    x_min = std::isfinite(x_min) && x_min < 1e300 ? x_min - 1 : 0;
    x_max = x_min + 2;
  }
  const int plot_w = kWidth - kLeft - kRight;
  const auto px = [&](double x) { return kLeft + static_cast<int>(std::lround((x - x_min) / (x_max - x_min) * plot_w)); };

  for (int p = 0; p < static_cast<int>(plot.panels.size()); ++p) {
    const PlotPanel& panel = plot.panels[static_cast<std::size_t>(p)];
    const int top = kTop + p * (kPanelHeight + kGap), bottom = top + kPanelHeight;
    double y_min = 0, y_max = 0;
    for (const PlotSeries& s : panel.series)
      for (double y : s.y)
        if (std::isfinite(y)) y_max = std::max(y_max, y), y_min = std::min(y_min, y);
    if (y_max <= y_min) y_max = y_min + 1;
    y_max += (y_max - y_min) * 0.05;
    const auto py = [&](double y) { return bottom - static_cast<int>(std::lround((y - y_min) / (y_max - y_min) * kPanelHeight)); };

    cv::rectangle(image, {kLeft, top}, {kLeft + plot_w, bottom}, cv::Scalar::all(120));
    for (int t = 0; t <= 4; ++t) {
      const double y = y_min + (y_max - y_min) * t / 4;
      cv::line(image, {kLeft, py(y)}, {kLeft + plot_w, py(y)}, cv::Scalar::all(230));
      text(image, number(y), {5, py(y) + 4}, 0.4);
    }
    // Whole-number ticks when the x values are small integers (pair indices), else five steps.
    const bool integer_axis = x_min == std::floor(x_min) && x_max == std::floor(x_max) && x_max - x_min <= 20;
    const int ticks = integer_axis ? static_cast<int>(x_max - x_min) : 5;
    for (int t = 0; t <= ticks; ++t) {
      const double x = x_min + (x_max - x_min) * t / ticks;
      text(image, number(x), {px(x) - 10, bottom + 16}, 0.4);
    }
    text(image, panel.y_label, {kLeft, top - 6}, 0.45);
    if (p + 1 == static_cast<int>(plot.panels.size())) text(image, plot.x_label, {kLeft + plot_w / 2 - 40, bottom + 36}, 0.45);

    for (std::size_t si = 0; si < panel.series.size(); ++si) {
      const PlotSeries& s = panel.series[si];
      const cv::Scalar color = kPalette[si % (sizeof kPalette / sizeof kPalette[0])];
      for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
        if (!std::isfinite(s.y[i])) continue;
        const cv::Point point(px(s.x[i]), py(s.y[i]));
        cv::circle(image, point, 3, color, cv::FILLED, cv::LINE_AA);
        if (i > 0 && std::isfinite(s.y[i - 1])) cv::line(image, {px(s.x[i - 1]), py(s.y[i - 1])}, point, color, 2, cv::LINE_AA);
      }
      const int ly = top + 18 + static_cast<int>(si) * 20;
      cv::line(image, {kLeft + plot_w + 10, ly - 4}, {kLeft + plot_w + 30, ly - 4}, color, 2, cv::LINE_AA);
      text(image, s.label, {kLeft + plot_w + 36, ly}, 0.42);
    }
    if (plot.marker_x) {
      const int x = px(*plot.marker_x);
      for (int y = top; y < bottom; y += 8) cv::line(image, {x, y}, {x, std::min(y + 4, bottom)}, cv::Scalar(0, 0, 0), 1);
      if (p == 0) {  // beside the line, on the side with room
        const int label_x = x > kLeft + plot_w - 130 ? x - 8 * static_cast<int>(plot.marker_label.size()) - 4 : x + 4;
        text(image, plot.marker_label, {label_x, top + 14}, 0.42);
      }
    }
  }
  bool ok = false;
  try {
    ok = cv::imwrite(path, image);
  } catch (const cv::Exception& e) {
    throw Error("cannot write plot '" + path + "': " + e.what());
  }
  if (!ok) throw Error("cannot write plot '" + path + "' (is the extension .png and the folder writable?)");
}

}  // namespace aief::io
