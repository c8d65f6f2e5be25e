#include "learn/imitation/demonstrations.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "core/error.hpp"
#include "core/file_io.hpp"
#include "learn/trainer/run_log.hpp"

namespace mimic {

int Demonstrations::episodes() const { return static_cast<int>(std::set<int>(episode.begin(), episode.end()).size()); }

void Demonstrations::append(const Demonstrations& more) {
  if (size() == 0 && obs.cols() == 0) {
    *this = more;
    return;
  }
  if (more.obs.cols() != obs.cols() || more.action.cols() != action.cols() || more.next_obs.cols() != next_obs.cols())
    throw Error("demonstrations of " + more.source + " (" + std::to_string(more.obs.cols()) + " observation and " +
                std::to_string(more.action.cols()) + " action values) do not match those of " + source + " (" +
                std::to_string(obs.cols()) + " and " + std::to_string(action.cols()) + ")");
  const auto same_slice = [](const ObservationSlice& a, const ObservationSlice& b) {
    return a.name == b.name && a.offset == b.offset && a.size == b.size;
  };
  if (!std::equal(layout.begin(), layout.end(), more.layout.begin(), more.layout.end(), same_slice))
    throw Error("demonstrations of " + more.source + " name other observation parts than those of " + source);
  const int offset = episode.empty() ? 0 : *std::max_element(episode.begin(), episode.end()) + 1;
  const Eigen::Index n = obs.rows();
  obs.conservativeResize(n + more.obs.rows(), Eigen::NoChange);
  action.conservativeResize(n + more.obs.rows(), Eigen::NoChange);
  next_obs.conservativeResize(n + more.obs.rows(), Eigen::NoChange);
  obs.bottomRows(more.obs.rows()) = more.obs;
  action.bottomRows(more.obs.rows()) = more.action;
  next_obs.bottomRows(more.obs.rows()) = more.next_obs;
  const int first = more.episode.empty() ? 0 : *std::min_element(more.episode.begin(), more.episode.end());
  for (int e : more.episode) episode.push_back(offset + e - first);
  source += " + " + more.source;
}

Demonstrations Demonstrations::first_episodes(int n) const {
  std::vector<int> order;  // episode tags in order of first appearance
  for (int e : episode)
    if (std::find(order.begin(), order.end(), e) == order.end()) order.push_back(e);
  const std::set<int> keep(order.begin(), order.begin() + std::min<std::ptrdiff_t>(n, static_cast<std::ptrdiff_t>(order.size())));
  std::vector<int> rows;
  for (int i = 0; i < size(); ++i)
    if (keep.count(episode[static_cast<std::size_t>(i)])) rows.push_back(i);
  Demonstrations d;
  d.source = source;
  d.layout = layout;
  d.obs.resize(static_cast<Eigen::Index>(rows.size()), obs.cols());
  d.action.resize(d.obs.rows(), action.cols());
  d.next_obs.resize(d.obs.rows(), next_obs.cols());
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const auto r = static_cast<Eigen::Index>(k);
    d.obs.row(r) = obs.row(rows[k]);
    d.action.row(r) = action.row(rows[k]);
    d.next_obs.row(r) = next_obs.row(rows[k]);
    d.episode.push_back(episode[static_cast<std::size_t>(rows[k])]);
  }
  return d;
}

namespace {

// Columns named prefix0, prefix1, ... in order, starting at `from`; returns how many.
int count_columns(const std::vector<std::string>& cols, std::size_t from, const std::string& prefix) {
  int n = 0;
  while (from + static_cast<std::size_t>(n) < cols.size() && cols[from + static_cast<std::size_t>(n)] == prefix + std::to_string(n)) ++n;
  return n;
}

constexpr const char* kLayoutPrefix = "# layout:";

std::vector<ObservationSlice> parse_layout(const std::string& line, const std::string& where) {
  std::vector<ObservationSlice> out;
  std::istringstream parts(line.substr(std::string(kLayoutPrefix).size()));
  std::string part;
  while (std::getline(parts, part, ';')) {
    std::istringstream in(part);
    ObservationSlice s;
    std::string extra;
    if (!(in >> s.name >> s.offset >> s.size) || (in >> extra) || s.offset < 0 || s.size < 1)
      throw ParseError(where, 1, "layout part '" + part + "' is not 'name offset size'");
    out.push_back(s);
  }
  return out;
}

}  // namespace

Demonstrations read_demonstrations(const std::filesystem::path& path) { return parse_demonstrations(read_text_file(path), path.string()); }

Demonstrations parse_demonstrations(std::string text, const std::string& where) {
  std::vector<ObservationSlice> layout;
  int first_line = 1;
  if (text.rfind(kLayoutPrefix, 0) == 0) {
    const std::size_t end = text.find('\n');
    layout = parse_layout(text.substr(0, end), where);
    text = end == std::string::npos ? std::string() : text.substr(end + 1);
    first_line = 2;
  }
  const MetricsTable t = parse_metrics_csv(text, where, first_line);
  const auto& c = t.columns;
  if (c.empty() || c[0] != "episode")
    throw ParseError(where, first_line, "not a demonstrations file: the header must start with 'episode,obs_0,...'");
  const int n_obs = count_columns(c, 1, "obs_");
  const int n_act = count_columns(c, 1 + static_cast<std::size_t>(n_obs), "action_");
  const int n_next = count_columns(c, 1 + static_cast<std::size_t>(n_obs + n_act), "next_obs_");
  if (n_obs == 0 || n_next != n_obs || c.size() != static_cast<std::size_t>(1 + n_obs + n_act + n_next))
    throw ParseError(where, first_line, fmt::format("header has {} obs_, {} action_ and {} next_obs_ columns in {} columns: expected "
                                           "episode, obs_0..obs_N-1, action_0..action_M-1, next_obs_0..next_obs_N-1",
                                           n_obs, n_act, n_next, c.size()));
  if (t.rows.empty()) throw ParseError(where, 0, "no samples");
  for (const auto& s : layout)
    if (s.offset + s.size > n_obs)
      throw ParseError(where, 1, fmt::format("layout part '{}' ({} values from {}) lies outside the {} observation values", s.name, s.size,
                                             s.offset, n_obs));
  Demonstrations d;
  d.source = where;
  d.layout = std::move(layout);
  const auto n = static_cast<Eigen::Index>(t.rows.size());
  d.obs.resize(n, n_obs);
  d.action.resize(n, n_act);
  d.next_obs.resize(n, n_obs);
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto& row = t.rows[static_cast<std::size_t>(i)];
    for (std::size_t k = 0; k < row.size(); ++k)
      if (!std::isfinite(row[k]))
        throw ParseError(where, static_cast<int>(i) + first_line + 1, fmt::format("column '{}' is empty or not finite", c[k]));
    if (row[0] != std::floor(row[0])) throw ParseError(where, static_cast<int>(i) + first_line + 1, "episode is not an integer");
    d.episode.push_back(static_cast<int>(row[0]));
    for (int k = 0; k < n_obs; ++k) d.obs(i, k) = row[static_cast<std::size_t>(1 + k)];
    for (int k = 0; k < n_act; ++k) d.action(i, k) = row[static_cast<std::size_t>(1 + n_obs + k)];
    for (int k = 0; k < n_obs; ++k) d.next_obs(i, k) = row[static_cast<std::size_t>(1 + n_obs + n_act + k)];
  }
  return d;
}

void write_demonstrations(const std::filesystem::path& path, const Demonstrations& d) {
  std::string out;
  if (!d.layout.empty()) {
    out = kLayoutPrefix;
    for (std::size_t i = 0; i < d.layout.size(); ++i)
      out += fmt::format("{} {} {} {}", i == 0 ? "" : ";", d.layout[i].name, d.layout[i].offset, d.layout[i].size);
    out += '\n';
  }
  out += "episode";
  for (int k = 0; k < d.obs.cols(); ++k) out += fmt::format(",obs_{}", k);
  for (int k = 0; k < d.action.cols(); ++k) out += fmt::format(",action_{}", k);
  for (int k = 0; k < d.next_obs.cols(); ++k) out += fmt::format(",next_obs_{}", k);
  out += '\n';
  for (int i = 0; i < d.size(); ++i) {
    out += std::to_string(d.episode[static_cast<std::size_t>(i)]);
    // Float precision: discriminators work in float32, and the files stay small.
    for (const Eigen::MatrixXd* m : {&d.obs, &d.action, &d.next_obs})
      for (int k = 0; k < m->cols(); ++k) out += fmt::format(",{:.7g}", (*m)(i, k));
    out += '\n';
  }
  write_file_atomic(path, out);
}

Demonstrations demonstrations_of(const Rollout& r, std::vector<ObservationSlice> layout, int every, std::mt19937_64& rng) {
  if (every < 1) throw Error("demonstrations: every must be >= 1");
  std::vector<std::pair<int, int>> kept;  // (sample, episode)
  int episode = 0;
  std::uniform_int_distribution<int> offset_of(0, every - 1);
  for (const auto& steps : r.env_steps) {
    int t = 0, offset = offset_of(rng);
    for (int i : steps) {
      if (t % every == offset) kept.emplace_back(i, episode);
      ++t;
      if (r.ended[static_cast<std::size_t>(i)]) ++episode, t = 0, offset = offset_of(rng);
    }
  }
  Demonstrations d;
  d.layout = std::move(layout);
  const auto n = static_cast<Eigen::Index>(kept.size());
  d.obs.resize(n, r.frame_size);
  d.next_obs.resize(n, r.frame_size);
  d.action.resize(n, r.action_size);
  for (Eigen::Index k = 0; k < n; ++k) {
    const auto [i, e] = kept[static_cast<std::size_t>(k)];
    d.obs.row(k) = r.frame(i).transpose();
    d.next_obs.row(k) = r.next_frame(i).transpose();
    d.action.row(k) = r.action_of(i).cast<double>().transpose();
    d.episode.push_back(e);
  }
  return d;
}

}  // namespace mimic
