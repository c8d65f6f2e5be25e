#include "render/line_chart.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>

#include <unistd.h>

#include <cstdlib>

#include "core/error.hpp"
#include "core/file_io.hpp"
#include "render/clip_svg.hpp"

namespace mimic {

std::vector<double> chart_ticks(double lo, double hi, int count) {
  if (!(hi > lo)) return {lo};
  const double raw = (hi - lo) / std::max(1, count);
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  double step = power;
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * power >= raw) {
      step = m * power;
      break;
    }
  std::vector<double> out;
  for (double t = std::ceil(lo / step) * step; t <= hi + 1e-9 * step; t += step) out.push_back(std::abs(t) < 1e-12 * step ? 0.0 : t);
  return out;
}

namespace {

// 1500 -> "1.5k", 2000000 -> "2M": sample counts stay short on the axis.
std::string label(double v) {
  const double a = std::abs(v);
  if (a >= 1e6) return fmt::format("{:g}M", v / 1e6);
  if (a >= 1e4) return fmt::format("{:g}k", v / 1e3);
  return fmt::format("{:g}", v);
}

}  // namespace

std::string line_chart_svg(const LineChart& c) {
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  for (const auto& s : c.series) {
    if (s.x.size() != s.y.size()) throw Error("chart series '" + s.name + "': x and y differ in length");
    const bool band = !s.band_low.empty() || !s.band_high.empty();
    if (band && (s.band_low.size() != s.x.size() || s.band_high.size() != s.x.size()))
      throw Error("chart series '" + s.name + "': its band's low and high values must be as many as its points");
    for (std::size_t i = 0; i < s.x.size(); ++i)
      if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) {
        x0 = std::min(x0, s.x[i]), x1 = std::max(x1, s.x[i]);
        y0 = std::min(y0, s.y[i]), y1 = std::max(y1, s.y[i]);
        if (band && std::isfinite(s.band_low[i]) && std::isfinite(s.band_high[i]))
          y0 = std::min(y0, s.band_low[i]), y1 = std::max(y1, s.band_high[i]);
      }
  }
  if (!std::isfinite(x0)) throw Error("chart '" + c.title + "': no finite points to draw");
  if (x1 == x0) x1 = x0 + 1;
  if (y1 == y0) y1 = y0 + 1;
  const std::vector<double> xt = chart_ticks(x0, x1), yt = chart_ticks(y0, y1);
  // The legend sits on the right; long names widen the picture, not shrink the plot.
  std::size_t longest = 0;
  for (const auto& s : c.series) longest = std::max(longest, s.name.size());
  const double legend = std::max(150.0, 30.0 + 7.0 * static_cast<double>(longest));
  const double width = c.width + (legend - 150.0);
  const double left = 70, right = 20 + legend, top = 40, bottom = 50;
  // A legend taller than the plot makes the picture taller (18 px a name), not runs off its foot.
  const double height = std::max(static_cast<double>(c.height), top + 20 + 18.0 * static_cast<double>(c.series.size()) + bottom);
  const double pw = width - left - right, ph = height - top - bottom;
  auto px = [&](double x) { return left + (x - x0) / (x1 - x0) * pw; };
  auto py = [&](double y) { return top + ph - (y - y0) / (y1 - y0) * ph; };
  // Ten colours, then the same ten dashed, then dotted: every series of a table-sized chart stays
  // told apart (the ten clips of seed 003 Table 1 drew two pairs alike with eight colours).
  static const char* colours[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd",
                                  "#8c564b", "#e377c2", "#17becf", "#7f7f7f", "#bcbd22"};
  static const char* dashes[] = {"", " stroke-dasharray='7 4'", " stroke-dasharray='2 3'"};
  auto colour_of = [&](std::size_t k) { return colours[k % std::size(colours)]; };
  auto dash_of = [&](std::size_t k) { return dashes[k / std::size(colours) % std::size(dashes)]; };

  std::string svg = fmt::format(
      "<svg xmlns='http://www.w3.org/2000/svg' width='{0}' height='{1}' viewBox='0 0 {0} {1}' font-family='sans-serif' font-size='12'>\n"
      "<rect width='100%' height='100%' fill='white'/>\n<text x='{2}' y='22' font-size='15'>{3}</text>\n",
      width, height, left, svg_escape(c.title));
  for (double t : xt)
    svg += fmt::format("<line x1='{0:.1f}' y1='{1:.1f}' x2='{0:.1f}' y2='{2:.1f}' stroke='#ddd'/><text x='{0:.1f}' y='{3:.1f}' text-anchor='middle'>{4}</text>\n",
                       px(t), top, top + ph, top + ph + 16, label(t));
  for (double t : yt)
    svg += fmt::format("<line x1='{0:.1f}' y1='{1:.1f}' x2='{2:.1f}' y2='{1:.1f}' stroke='#ddd'/><text x='{3:.1f}' y='{4:.1f}' text-anchor='end'>{5}</text>\n",
                       left, py(t), left + pw, left - 6, py(t) + 4, label(t));
  svg += fmt::format("<rect x='{}' y='{}' width='{}' height='{}' fill='none' stroke='#444'/>\n", left, top, pw, ph);
  svg += fmt::format("<text x='{:.1f}' y='{:.1f}' text-anchor='middle'>{}</text>\n", left + pw / 2, height - 10.0, svg_escape(c.x_label));
  svg += fmt::format("<text transform='translate(16 {:.1f}) rotate(-90)' text-anchor='middle'>{}</text>\n", top + ph / 2, svg_escape(c.y_label));
  // Bands first, so that no band hides another series' line.
  for (std::size_t k = 0; k < c.series.size(); ++k) {
    const auto& s = c.series[k];
    if (s.band_low.empty()) continue;
    std::string upper, lower;  // one polygon per run of points with a finite band
    auto flush = [&] {
      if (!upper.empty()) svg += fmt::format("<polygon fill='{}' fill-opacity='0.15' stroke='none' points='{}{}'/>\n", colour_of(k), upper, lower);
      upper.clear(), lower.clear();
    };
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i]) || !std::isfinite(s.band_low[i]) || !std::isfinite(s.band_high[i])) {
        flush();
        continue;
      }
      upper += fmt::format("{:.1f},{:.1f} ", px(s.x[i]), py(s.band_high[i]));
      lower = fmt::format("{:.1f},{:.1f} ", px(s.x[i]), py(s.band_low[i])) + lower;
    }
    flush();
  }
  for (std::size_t k = 0; k < c.series.size(); ++k) {
    const auto& s = c.series[k];
    const char* colour = colour_of(k);
    const char* dash = dash_of(k);
    std::string pts;
    auto flush = [&] {
      if (!pts.empty()) svg += fmt::format("<polyline fill='none' stroke='{}' stroke-width='1.6'{} points='{}'/>\n", colour, dash, pts);
      pts.clear();
    };
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) {
        flush();
        continue;
      }
      pts += fmt::format("{:.1f},{:.1f} ", px(s.x[i]), py(s.y[i]));
    }
    flush();
    const double ly = top + 10 + 18.0 * static_cast<double>(k);
    svg += fmt::format("<line x1='{0:.1f}' y1='{1:.1f}' x2='{2:.1f}' y2='{1:.1f}' stroke='{3}' stroke-width='3'{4}/><text x='{5:.1f}' y='{6:.1f}'>{7}</text>\n",
                       left + pw + 10, ly, left + pw + 30, colour, dash, left + pw + 36, ly + 4, svg_escape(s.name));
  }
  svg += "</svg>\n";
  return svg;
}

namespace {

std::string shell_quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace

void write_line_chart(const std::filesystem::path& out, const LineChart& chart) {
  const std::string ext = out.extension().string();
  if (ext != ".svg" && ext != ".png") throw Error(out.string() + ": a chart is written as .svg or .png");
  const std::string svg = line_chart_svg(chart);
  if (ext == ".svg") return write_file_atomic(out, svg);
  if (out.has_parent_path()) std::filesystem::create_directories(out.parent_path());
  std::filesystem::path source = out, partial = out;
  source += ".partial" + std::to_string(::getpid()) + ".svg";
  partial += ".partial" + std::to_string(::getpid()) + ".png";
  write_file_atomic(source, svg);
  const std::string cmd = fmt::format("ffmpeg -loglevel error -y -i {} -frames:v 1 -c:v png -f image2 {}", shell_quoted(source.string()),
                                      shell_quoted(partial.string()));
  const int status = std::system(cmd.c_str());
  std::error_code ec;
  std::filesystem::remove(source, ec);
  if (status != 0 || !std::filesystem::exists(partial)) {
    std::filesystem::remove(partial, ec);
    throw Error(out.string() + ": ffmpeg could not rasterise the chart (exit status " + std::to_string(status) +
                "; it needs ffmpeg with librsvg, installed by scripts/setup.sh)");
  }
  std::filesystem::rename(partial, out);
}

}  // namespace mimic
