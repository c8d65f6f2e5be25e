#pragma once
// A training run's metrics: one CSV row per iteration (metrics.csv) and TensorBoard scalars
// (tensorboard/events.*). On resume the CSV, read back whole first (an Error naming the file and
// line, nothing changed, where it does not parse), keeps only the rows up to the checkpoint's
// iteration, and the old event files only the steps up to it, so that no step is written twice;
// TensorBoard gets a new event file.
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace mimic {

class TensorBoardWriter;

// Named values of one iteration in a fixed order; NaN means "none this iteration" (an empty
// CSV field, no TensorBoard point).
struct IterationMetrics {
  int iteration = 0;
  std::vector<std::pair<std::string, double>> values;
  void set(const std::string& name, double v);
  double get(const std::string& name) const;  // NaN when absent
};

class RunLog {
 public:
  // `resume_iteration` >= 0 keeps the existing CSV's rows up to that iteration.
  RunLog(const std::filesystem::path& run_dir, bool tensorboard, int resume_iteration);
  ~RunLog();
  void write(const IterationMetrics& m);
  const std::filesystem::path& csv_path() const { return csv_path_; }

 private:
  std::filesystem::path csv_path_;
  std::ofstream csv_;
  std::vector<std::string> columns_;
  std::unique_ptr<TensorBoardWriter> tb_;
};

// Reads a metrics CSV back (header names, then rows; empty fields are NaN). Error on a ragged
// or non-numeric row, naming the file and line.
struct MetricsTable {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
  std::vector<double> column(const std::string& name) const;
};
MetricsTable read_metrics_csv(const std::filesystem::path& path);
// The same from text; `source` names it in errors, whose line numbers start at `first_line`.
MetricsTable parse_metrics_csv(const std::string& text, const std::string& source, int first_line = 1);

}  // namespace mimic
