#include "control/performing.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "control/play_session.hpp"
#include "core/error.hpp"
#include "core/statistics.hpp"

namespace mimic {

double PerformingReport::mean() const { return mean_of(fractions); }

double PerformingReport::std() const { return std_of(fractions); }

double PerformingReport::mean_downs() const { return mean_of(std::vector<double>(downs.begin(), downs.end())); }

double PerformingReport::mean_recoveries() const { return mean_of(std::vector<double>(recoveries.begin(), recoveries.end())); }

PerformingReport measure_performing(const std::vector<std::shared_ptr<const Skill>>& skills, const PerformingOptions& options) {
  if (skills.empty()) throw Error("performing: give the skill that performs");
  if (!(options.seconds > 0) || !std::isfinite(options.seconds) || options.trials < 1)
    throw Error("performing: the seconds must be positive and the trials at least 1");
  PlayOptions play;
  play.hand_back_threshold = options.hand_back_threshold;
  play.seed = options.seed;
  for (std::size_t i = 1; i < skills.size(); ++i) play.recovery.push_back(skills[i]->name());
  PlaySession session(skills, play);
  const std::string& performer = skills.front()->name();
  const long long steps = std::max(1LL, std::llround(options.seconds / session.controller().control_dt()));
  PerformingReport report;
  report.seconds = options.seconds;
  for (int trial = 0; trial < options.trials; ++trial) {
    if (trial > 0) session.reset();  // (the session starts with its first episode)
    const std::size_t first_event = session.events().size();
    long long performing = 0;
    for (long long t = 0; t < steps; ++t) {
      session.step();
      if (!session.down() && !session.recovering() && session.controller().skill() == performer) ++performing;
    }
    int downs = 0, recovered = 0;
    for (std::size_t e = first_event; e < session.events().size(); ++e) {
      downs += session.events()[e].event == "down";
      recovered += session.events()[e].event == "recovered";
    }
    report.fractions.push_back(static_cast<double>(performing) / static_cast<double>(steps));
    report.downs.push_back(downs);
    report.recoveries.push_back(recovered);
  }
  return report;
}

}  // namespace mimic
