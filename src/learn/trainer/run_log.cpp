#include "learn/trainer/run_log.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <sstream>

#include <fmt/format.h>

#include "core/error.hpp"
#include "core/file_io.hpp"
#include "core/tensorboard.hpp"

namespace mimic {

void IterationMetrics::set(const std::string& name, double v) {
  for (auto& [n, x] : values)
    if (n == name) {
      x = v;
      return;
    }
  values.emplace_back(name, v);
}

double IterationMetrics::get(const std::string& name) const {
  for (const auto& [n, x] : values)
    if (n == name) return x;
  return std::numeric_limits<double>::quiet_NaN();
}

namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) out.push_back(cell);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

}  // namespace

MetricsTable read_metrics_csv(const std::filesystem::path& path) { return parse_metrics_csv(read_text_file(path), path.string()); }

MetricsTable parse_metrics_csv(const std::string& text, const std::string& source, int first_line) {
  std::istringstream in(text);
  std::string line;
  MetricsTable t;
  int line_no = first_line - 1;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty()) continue;
    if (t.columns.empty()) {
      t.columns = split(line);
      continue;
    }
    const auto cells = split(line);
    if (cells.size() != t.columns.size())
      throw ParseError(source, line_no, fmt::format("{} fields, the header has {}", cells.size(), t.columns.size()));
    std::vector<double> row;
    for (const auto& c : cells) {
      if (c.empty()) {
        row.push_back(std::numeric_limits<double>::quiet_NaN());
        continue;
      }
      std::size_t used = 0;
      double v = 0;
      try {
        v = std::stod(c, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != c.size()) throw ParseError(source, line_no, "'" + c + "' is not a number");
      row.push_back(v);
    }
    t.rows.push_back(std::move(row));
  }
  return t;
}

std::vector<double> MetricsTable::column(const std::string& name) const {
  for (std::size_t c = 0; c < columns.size(); ++c)
    if (columns[c] == name) {
      std::vector<double> out;
      for (const auto& r : rows) out.push_back(r[c]);
      return out;
    }
  throw Error("metrics: no column '" + name + "'");
}

namespace {

// The rows of a resumed run's metrics.csv up to its checkpoint's iteration, as text, after the
// whole file has been read back: a header of column names starting with "iteration", then rows
// that parse, in order. Only a last line without its newline (a row cut by a kill, which is
// always after the checkpoint's rows) may be dropped unread. Error naming the file and the line,
// the file untouched, otherwise.
std::string rows_to_keep(const std::filesystem::path& csv, int resume_iteration, std::vector<std::string>& columns) {
  std::string text = read_text_file(csv);
  if (!text.empty() && text.back() != '\n') text.erase(text.rfind('\n') == std::string::npos ? 0 : text.rfind('\n') + 1);
  const std::string refuse = "; the run was not resumed, so that no row of it is lost: repair the file or move it away";
  MetricsTable table;
  try {
    table = parse_metrics_csv(text, csv.string());
  } catch (const Error& e) {
    throw Error(e.what() + refuse);
  }
  if (table.columns.empty()) return "";
  const bool named = std::all_of(table.columns.begin(), table.columns.end(), [](const std::string& c) {
    return !c.empty() && std::all_of(c.begin(), c.end(), [](char ch) { return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_'; });
  });
  if (table.columns.front() != "iteration" || !named)
    throw ParseError(csv.string(), 1, "not a metrics header (column names of letters, digits and '_', 'iteration' first)" + refuse);
  double previous = 0;
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    const double it = table.rows[r].front();
    if (!(it > previous) || it != std::floor(it))
      throw ParseError(csv.string(), static_cast<int>(r) + 2, "iteration " + std::to_string(it) + " does not follow " + std::to_string(previous) + refuse);
    previous = it;
  }
  columns = table.columns;
  std::istringstream in(text);
  std::string line, kept;
  std::size_t row = 0;
  for (bool header = true; std::getline(in, line);) {
    if (line.empty()) continue;
    if (!header && table.rows[row++].front() > resume_iteration) break;
    kept += line + "\n";
    header = false;
  }
  return kept;
}

}  // namespace

RunLog::RunLog(const std::filesystem::path& run_dir, bool tensorboard, int resume_iteration)
    : csv_path_(run_dir / "metrics.csv") {
  std::filesystem::create_directories(run_dir);
  if (resume_iteration >= 0 && std::filesystem::exists(csv_path_)) {
    // Keep the header and the rows the checkpoint covers; rows written after it are redone.
    write_file_atomic(csv_path_, rows_to_keep(csv_path_, resume_iteration, columns_));
  } else {
    write_file_atomic(csv_path_, "");
  }
  csv_.open(csv_path_, std::ios::app);
  if (!csv_) throw Error(csv_path_.string() + ": cannot open for writing");
  if (tensorboard) {
    // Steps after the checkpoint are written again by the resumed run: the old ones go first.
    if (resume_iteration >= 0) truncate_tensorboard_events(run_dir / "tensorboard", resume_iteration);
    tb_ = std::make_unique<TensorBoardWriter>(run_dir / "tensorboard");
  }
}

RunLog::~RunLog() = default;

void RunLog::write(const IterationMetrics& m) {
  if (columns_.empty()) {
    columns_.push_back("iteration");
    for (const auto& [n, v] : m.values) columns_.push_back(n);
    std::string header;
    for (const auto& c : columns_) header += (header.empty() ? "" : ",") + c;
    csv_ << header << '\n';
  }
  std::string row = std::to_string(m.iteration);
  for (std::size_t c = 1; c < columns_.size(); ++c) {
    const double v = m.get(columns_[c]);
    row += ',';
    if (std::isfinite(v)) row += fmt::format("{:.9g}", v);
  }
  csv_ << row << '\n';
  csv_.flush();
  if (!csv_) throw Error(csv_path_.string() + ": write failed");
  if (tb_) {
    for (const auto& [n, v] : m.values)
      if (std::isfinite(v)) tb_->scalar(n, v, m.iteration);
    tb_->flush();
  }
}

}  // namespace mimic
