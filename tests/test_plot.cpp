// Plots a reader trusts: round tick values spanning the data, and series told apart by colour and
// marker (io/plot_axis.hpp, io/plot.hpp).
#include <set>
#include <tuple>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "aief/error.hpp"
#include "io/plot.hpp"
#include "io/plot_axis.hpp"
#include "tests/test_support.hpp"

namespace aief::io {
namespace {

TEST(RoundTicks, AreRoundValuesSpanningTheData) {
  // The figures the old plots printed: 482 / 361 / 89.83 came from dividing the data's maximum.
  const AxisTicks counts = round_ticks(0, 461);
  EXPECT_DOUBLE_EQ(counts.step, 100);
  EXPECT_EQ(counts.values, (std::vector<double>{0, 100, 200, 300, 400, 500}));
  EXPECT_EQ(counts.label(300), "300");

  const AxisTicks percent = round_ticks(0, 85.3);
  EXPECT_DOUBLE_EQ(percent.step, 20);
  EXPECT_DOUBLE_EQ(percent.values.back(), 100);

  const AxisTicks bits = round_ticks(0, 7.6, 8);
  EXPECT_DOUBLE_EQ(bits.step, 1);
  EXPECT_DOUBLE_EQ(bits.values.back(), 8);

  const AxisTicks quarter = round_ticks(0, 1.1, 5);
  EXPECT_DOUBLE_EQ(quarter.step, 0.25);
  EXPECT_EQ(quarter.label(0.75), "0.75");
  EXPECT_EQ(quarter.label(1), "1.00");
}

TEST(RoundTicks, CoverTheDataWhateverItIs) {
  for (const auto& [lo, hi] : std::vector<std::pair<double, double>>{
           {0, 0}, {5, 5}, {-3, 17}, {0.001, 0.0042}, {12, 1e6}}) {
    const AxisTicks ticks = round_ticks(lo, hi);
    ASSERT_GE(ticks.values.size(), 2u) << lo << " " << hi;
    EXPECT_LE(ticks.values.front(), lo);
    EXPECT_GE(ticks.values.back(), hi);
    EXPECT_LE(ticks.values.size(), 12u) << lo << " " << hi;
  }
  EXPECT_EQ(round_ticks(-10, 10).label(-0.0), "0");  // never "-0"
  EXPECT_EQ(round_ticks(-1, 1).label(-0.0), "0.0");
}

TEST(SeriesStyle, NoTwoSeriesLookAlike) {
  std::set<std::tuple<int, int, int>> colours;
  std::set<Marker> markers;
  std::set<std::tuple<int, int, int, Marker>> styles;
  for (std::size_t i = 0; i < 8; ++i) {
    const SeriesStyle s = series_style(i);
    colours.insert({s.red, s.green, s.blue});
    markers.insert(s.marker);
  }
  EXPECT_EQ(colours.size(), 8u);  // the evaluation's eight methods
  EXPECT_EQ(markers.size(), 8u);
  for (std::size_t i = 0; i < 40; ++i) {
    const SeriesStyle s = series_style(i);
    styles.insert({s.red, s.green, s.blue, s.marker});
  }
  EXPECT_EQ(styles.size(), 40u);
}

TEST(WritePlot, WritesAPngAndRefusesAnUnwritablePath) {
  const test::TempFolder dir;
  Plot plot;
  plot.title = "t";
  plot.x_label = "F (bits)";
  plot.panels = {{"count", {{"a", {0, 0.5, 1}, {3, 1, 2}}, {"b", {0, 0.5, 1}, {3, 1, 2}}}}};
  plot.marker_x = 0.5;
  plot.marker_label = "chosen F = 0.5";
  const std::string path = dir.file("plot.png");
  write_plot_png(path, plot);
  EXPECT_FALSE(cv::imread(path).empty());
  EXPECT_THROW(write_plot_png(dir.file("missing/plot.png"), plot), Error);
}

}  // namespace
}  // namespace aief::io
