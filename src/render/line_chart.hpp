#pragma once
// Line charts as SVG (learning curves, robustness curves): series of (x, y) points on shared
// axes with round-number ticks and a legend. Points with a non-finite y are gaps.
#include <filesystem>
#include <string>
#include <vector>

namespace mimic {

struct ChartSeries {
  std::string name;
  std::vector<double> x, y;
  // Optional shaded band from band_low to band_high at each x (a spread around y, as seed 004
  // Fig. 7's ± one standard deviation): both empty, or both as long as x.
  std::vector<double> band_low = {}, band_high = {};
};

struct LineChart {
  std::string title, x_label, y_label;
  std::vector<ChartSeries> series;
  int width = 720, height = 420;
};

// The SVG text; Error when there is nothing finite to draw or a series' x, y or band sizes differ.
std::string line_chart_svg(const LineChart& chart);
// The chart to `out`: .svg as written by line_chart_svg, .png rasterised from it by ffmpeg's SVG
// decoder (librsvg). Atomic: a failure leaves no partial file. Error naming the file otherwise.
void write_line_chart(const std::filesystem::path& out, const LineChart& chart);
// "Nice" tick values covering [lo, hi] (1, 2 or 5 times a power of ten apart), about `count`.
std::vector<double> chart_ticks(double lo, double hi, int count = 5);

}  // namespace mimic
