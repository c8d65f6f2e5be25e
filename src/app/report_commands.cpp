// mimic plot (learning curves from metrics.csv, robustness curves from `mimic eval --json`
// files; .svg or .png) and mimic table (a Markdown table of `mimic eval --json` files, with the
// training budget behind each): the figures of the docs, made by commands.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>

#include "app/commands.hpp"
#include "app/eval_file.hpp"
#include "core/error.hpp"
#include "core/file_io.hpp"
#include "core/yaml_reader.hpp"
#include "learn/trainer/run_log.hpp"
#include "render/line_chart.hpp"

namespace mimic::app {

namespace {

// Moving average over the last `window` finite values (NaN where none).
std::vector<double> smooth(const std::vector<double>& v, int window) {
  std::vector<double> out(v.size(), std::nan(""));
  for (std::size_t i = 0; i < v.size(); ++i) {
    double sum = 0;
    int n = 0;
    for (std::size_t j = i + 1 > static_cast<std::size_t>(window) ? i + 1 - static_cast<std::size_t>(window) : 0; j <= i; ++j)
      if (std::isfinite(v[j])) sum += v[j], ++n;
    if (n > 0) out[i] = sum / n;
  }
  return out;
}

std::string cell(double v, const char* format) { return std::isfinite(v) ? fmt::format(fmt::runtime(format), v) : std::string("-"); }

// Samples and wall time behind a run: the last row of its metrics.csv, or where the run is gone, of
// the copy kept beside its evaluation (<eval>.csv beside <eval>.json: the scripts' committed
// results); "-" where neither is there.
std::pair<std::string, std::string> budget_of(const std::filesystem::path& run, const std::filesystem::path& eval_json) {
  std::filesystem::path csv = run / "metrics.csv";
  if (!std::filesystem::exists(csv)) csv = std::filesystem::path(eval_json).replace_extension(".csv");
  if (!std::filesystem::exists(csv)) {
    spdlog::warn("{} not found, nor {}: no budget for that row (the run's path is as mimic eval was given it, relative to where it ran)",
                 (run / "metrics.csv").string(), csv.string());
    return {"-", "-"};
  }
  const MetricsTable t = read_metrics_csv(csv);
  if (t.rows.empty()) return {"-", "-"};
  const std::vector<double> samples = t.column("samples"), wall = t.column("wall_s");
  return {cell(samples.back() / 1e6, "{:.2f} M"), cell(wall.back() / 60.0, "{:.0f} min")};
}

struct PlotArgs {
  std::vector<std::filesystem::path> inputs;
  std::vector<std::string> names;
  std::filesystem::path out;
  std::string x = "samples", y = "return", title;
  int smooth = 1;
};

std::string name_of(const PlotArgs& a, std::size_t i, const std::filesystem::path& file) {
  if (!a.names.empty()) return a.names[i];
  return std::filesystem::is_directory(a.inputs[i]) ? a.inputs[i].filename().string() : file.stem().string();
}

LineChart learning_chart(const PlotArgs& a) {
  LineChart chart;
  chart.x_label = a.x;
  chart.y_label = a.y + (a.smooth > 1 ? fmt::format(" (mean of {} iterations)", a.smooth) : "");
  chart.title = a.title.empty() ? a.y + " vs " + a.x : a.title;
  for (std::size_t i = 0; i < a.inputs.size(); ++i) {
    const std::filesystem::path csv = std::filesystem::is_directory(a.inputs[i]) ? a.inputs[i] / "metrics.csv" : a.inputs[i];
    const MetricsTable t = read_metrics_csv(csv);
    ChartSeries s;
    s.name = name_of(a, i, csv);
    try {
      s.x = t.column(a.x);
      s.y = smooth(t.column(a.y), a.smooth);
    } catch (const Error& e) {
      throw Error(csv.string() + ": " + e.what());
    }
    chart.series.push_back(std::move(s));
  }
  return chart;
}

// One point's band, y ± sd cut to [0, top]; none (NaN) without a spread (older files have none).
void add_band(ChartSeries& s, double y, double sd, double top) {
  const double none = std::numeric_limits<double>::quiet_NaN();
  s.band_low.push_back(std::isfinite(sd) ? std::max(0.0, y - sd) : none);
  s.band_high.push_back(std::isfinite(sd) ? std::min(top, y + sd) : none);
}

// Seed 004 Fig. 7: frames survived against projectile mass, one line per evaluation, shaded ± one
// standard deviation of the trials, cut at 0 and at the trials' length (frames cannot go past them).
LineChart robustness_chart(const PlotArgs& a) {
  LineChart chart;
  chart.x_label = "projectile mass (kg)";
  chart.y_label = "frames survived (mean, shaded ± s.d. of trials)";
  chart.title = a.title.empty() ? "Robustness to projectiles" : a.title;
  for (std::size_t i = 0; i < a.inputs.size(); ++i) {
    const EvalSummary e = read_eval_json(a.inputs[i]);
    if (e.masses.empty()) throw Error(a.inputs[i].string() + ": no robustness figures (evaluate with mimic eval --robustness)");
    ChartSeries s{name_of(a, i, a.inputs[i]), e.masses, e.frames};
    for (std::size_t j = 0; j < e.masses.size(); ++j)
      add_band(s, e.frames[j], e.frames_std[j], std::isfinite(e.max_frames[j]) ? e.max_frames[j] : e.frames[j] + e.frames_std[j]);
    chart.series.push_back(std::move(s));
  }
  return chart;
}

// Robustness with recovery (mimic eval --recover): the time spent performing against cube mass,
// two lines per evaluation (without and with the get-ups), shaded ± one s.d. of the trials.
LineChart recovery_chart(const PlotArgs& a) {
  LineChart chart;
  chart.x_label = "projectile mass (kg)";
  chart.y_label = "time performing (%, mean, shaded ± s.d. of trials)";
  chart.title = a.title.empty() ? "Robustness with recovery" : a.title;
  for (std::size_t i = 0; i < a.inputs.size(); ++i) {
    const EvalSummary e = read_eval_json(a.inputs[i]);
    if (e.recovery.empty()) throw Error(a.inputs[i].string() + ": no recovery figures (evaluate with mimic eval --robustness ... --recover GETUP)");
    for (const bool with : {false, true}) {
      ChartSeries s{name_of(a, i, a.inputs[i]) + (with ? " with recovery" : " without recovery"), {}, {}};
      for (const auto& p : e.recovery) {
        const double y = 100.0 * (with ? p.with : p.without), sd = 100.0 * (with ? p.with_std : p.without_std);
        s.x.push_back(p.mass), s.y.push_back(y);
        add_band(s, y, sd, 100.0);
      }
      chart.series.push_back(std::move(s));
    }
  }
  return chart;
}

// Seed 004 Fig. 10: switch success against the threshold tau, one line per rule, each point the
// mean over the file's ordered pairs of skills (switching at once: flat, it has no tau); with
// --y wait, the mean wait from request to take-over over the pairs where any request was granted.
LineChart transitions_chart(const PlotArgs& a) {
  if (a.inputs.size() != 1) throw Error("plot: transition curves come from one evaluation file");
  const EvalSummary e = read_eval_json(a.inputs.front());
  const bool wait = a.y == "wait";
  if (!wait && a.y != "success" && a.y != "return")  // ("return": --y's default, for learning curves)
    throw Error("--y: transition curves plot 'success' (the default) or 'wait'");
  LineChart chart;
  chart.x_label = "threshold tau";
  chart.y_label = wait ? "mean wait from request to take-over (s), over the pairs" : "switch success (%), mean over the pairs";
  chart.title = a.title.empty() ? "Switching between skills" : a.title;
  std::map<std::string, std::map<double, std::vector<double>>> by_rule;  // rule -> tau -> figures of the pairs
  double lo = INFINITY, hi = -INFINITY;
  for (const auto& t : e.transitions) {
    const double y = wait ? t.mean_wait : 100.0 * t.success_rate;
    if (t.rule != "immediately") lo = std::min(lo, t.threshold), hi = std::max(hi, t.threshold);
    if (std::isfinite(y)) by_rule[t.rule][t.rule == "immediately" ? 0.0 : t.threshold].push_back(y);
  }
  if (e.transitions.empty()) throw Error(a.inputs.front().string() + ": no transition figures (evaluate with mimic eval --transitions)");
  for (const char* rule : {"score", "value", "matching", "immediately"}) {
    const auto it = by_rule.find(rule);
    if (it == by_rule.end()) continue;
    ChartSeries s{std::string(rule) == "immediately" ? "at once" : std::string("by ") + rule, {}, {}};
    for (const auto& [tau, ys] : it->second) {
      const double mean = std::accumulate(ys.begin(), ys.end(), 0.0) / static_cast<double>(ys.size());
      if (std::string(rule) == "immediately" && std::isfinite(lo)) {
        s.x = {lo, hi}, s.y = {mean, mean};
      } else {
        s.x.push_back(tau), s.y.push_back(mean);
      }
    }
    chart.series.push_back(std::move(s));
  }
  return chart;
}

}  // namespace

void add_report_commands(CLI::App& app) {
  auto plot_args = std::make_shared<PlotArgs>();
  CLI::App* plot = app.add_subcommand("plot", "learning curves (runs' metrics.csv), robustness or transition curves (mimic eval --json files) as .svg or .png");
  plot->add_option("inputs", plot_args->inputs, "run directories or metrics.csv files; or evaluation .json files")
      ->required()
      ->check(CLI::ExistingPath);
  plot->add_option("-o,--output", plot_args->out, "output .svg or .png")->required();
  plot->add_option("--x", plot_args->x, "column on the x axis (learning curves)")->capture_default_str();
  plot->add_option("--y", plot_args->y,
                   "column on the y axis (learning curves); for evaluation files: wait (transition waits), performing (robustness with recovery)")
      ->capture_default_str();
  plot->add_option("--smooth", plot_args->smooth, "moving average over this many iterations")->capture_default_str()->check(CLI::PositiveNumber);
  plot->add_option("--names", plot_args->names, "legend names, one per input (default: the directories' or files' names)");
  plot->add_option("--title", plot_args->title, "chart title");
  plot->callback([plot_args] {
    const PlotArgs& a = *plot_args;
    if (!a.names.empty() && a.names.size() != a.inputs.size()) throw Error("--names: give one name per input");
    const auto is_json = [](const std::filesystem::path& p) { return p.extension() == ".json"; };
    const std::size_t json = static_cast<std::size_t>(std::count_if(a.inputs.begin(), a.inputs.end(), is_json));
    if (json != 0 && json != a.inputs.size()) throw Error("plot: give either runs (learning curves) or evaluation .json files (robustness), not both");
    bool transitions = false;
    if (json == 1) {
      const EvalSummary only = read_eval_json(a.inputs.front());
      transitions = only.masses.empty() && !only.transitions.empty();
    }
    const bool recovery = json && a.y == "performing";
    const LineChart chart = recovery ? recovery_chart(a) : transitions ? transitions_chart(a) : json ? robustness_chart(a) : learning_chart(a);
    write_line_chart(a.out, chart);
    spdlog::info("wrote {} ({} input(s), {})", a.out.string(), a.inputs.size(),
                 recovery ? "robustness with recovery" : transitions ? "transitions" : json ? "robustness" : a.y + " vs " + a.x);
  });

  struct TableArgs {
    std::vector<std::filesystem::path> inputs;
    std::vector<std::string> names;
    std::filesystem::path out;
  };
  auto table_args = std::make_shared<TableArgs>();
  CLI::App* table = app.add_subcommand("table", "a Markdown table of evaluations (mimic eval --json files) with each run's training budget, or of reconstructions (mimic reconstruct --json)");
  table->add_option("inputs", table_args->inputs, "evaluation (or reconstruction) .json files")->required()->check(CLI::ExistingFile);
  table->add_option("--names", table_args->names, "row names, one per file (default: the runs' directories)");
  table->add_option("-o,--output", table_args->out, "also write the table to this file");
  table->callback([table_args] {
    const TableArgs& a = *table_args;
    if (!a.names.empty() && a.names.size() != a.inputs.size()) throw Error("--names: give one name per file");
    if (is_reconstruction_report(a.inputs.front())) {  // mimic reconstruct --json files
      const std::string rec = reconstruction_table(a.inputs, a.names);
      fmt::print("{}", rec);
      if (!a.out.empty()) write_file_atomic(a.out, rec);
      return;
    }
    std::string text =
        "| run | clip | samples | wall | imitation error (m) | normalised return | falls | down | episode length | progress |\n"
        "|---|---|---|---|---|---|---|---|---|---|\n";
    for (std::size_t i = 0; i < a.inputs.size(); ++i) {
      const EvalSummary e = read_eval_json(a.inputs[i]);
      const auto [samples, wall] = budget_of(e.run, a.inputs[i]);
      const std::string error = std::isfinite(e.error_mean) ? fmt::format("{:.3f} ± {:.3f}", e.error_mean, e.error_std) : "-";
      const std::string falls = e.falls >= 0 ? fmt::format("{} / {}", e.falls, e.trials) : "-";
      const std::string down = e.down >= 0 ? fmt::format("{} / {}", e.down, e.trials) : "-";
      text += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", a.names.empty() ? e.run : a.names[i],
                          e.clip.empty() ? "-" : e.clip, samples, wall, error, cell(e.normalised_return, "{:.3f}"), falls, down,
                          cell(e.episode_length, "{:.0f}"), cell(e.progress, "{:.2f}"));
    }
    fmt::print("{}", text);
    if (!a.out.empty()) write_file_atomic(a.out, text);
  });
}

}  // namespace mimic::app
