#pragma once
// Reading back a `mimic eval --json` file: for plot, table and imitate's report.
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace mimic::app {

// The figures of one `mimic eval --json` file that the reports use (NaN where absent or null).
struct EvalSummary {
  std::string run, clip;
  double error_mean = NAN, error_std = NAN, normalised_return = NAN, progress = NAN, episode_length = NAN, return_mean = NAN;
  long falls = -1, down = -1, trials = 0;
  std::vector<double> masses, frames, frames_std, max_frames;  // robustness (NaN: not in the file)
  struct Transition {  // one cell of the transition test (mimic eval --transitions)
    std::string from, to, rule;
    double threshold = NAN, success_rate = NAN, mean_wait = NAN;
  };
  std::vector<Transition> transitions;
  struct Recovery {  // one cube mass of robustness with recovery (mimic eval --recover): fractions of the time performing
    double mass = NAN, without = NAN, without_std = NAN, with = NAN, with_std = NAN;
  };
  std::vector<Recovery> recovery;
};

// Error naming the file when it is not such a file.
EvalSummary read_eval_json(const std::filesystem::path& path);

}  // namespace mimic::app
