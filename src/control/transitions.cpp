#include "control/transitions.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include "core/error.hpp"
#include "env/down_rule.hpp"

namespace mimic {

namespace {

struct Trial {
  bool valid = false, switched = false, succeeded = false, fell = false;
  double wait = 0.0;
};

// One trial: `from` from its start, the request after `request_steps`, then the hold.
Trial run_trial(Controller& c, const std::string& from, const std::string& to, int request_steps, const TransitionOptions& o) {
  Trial t;
  c.switch_to(from);
  c.reset();
  for (int i = 0; i < request_steps; ++i)
    if (c.step().episode_over) return t;  // the first skill ended (fell) before the request: drawn again
  t.valid = true;
  // Down: the root below half its height at the request for 10 consecutive frames (the robustness
  // protocol's lying rule). The skills' own episode ends (any elbow touching the floor, a drift
  // from their clip's line) are training's rules, not this test's.
  const double standing = c.root_position().z();
  DownRule lying(standing);
  auto down = [&] { return lying.update(c.root_position().z()); };
  c.request(to);
  const double dt = c.control_dt();
  const int limit = static_cast<int>(std::ceil(o.time_limit_seconds / dt)) + 1;
  for (int i = 1; i <= limit; ++i) {
    const StepInfo info = c.step();
    if (!info.switched_to.empty()) {
      t.switched = true;
      t.wait = i * dt;
      break;
    }
    if (!info.dropped.empty() || down()) return t;
  }
  if (!t.switched) return t;
  lying.restart(standing);
  const int hold = static_cast<int>(std::lround(o.hold_seconds / dt)), last_second = static_cast<int>(std::lround(1.0 / dt));
  double score_sum = 0.0;
  int scored = 0;
  for (int i = 0; i < hold; ++i) {
    (void)c.step();
    if (down()) {
      t.fell = true;
      return t;
    }
    if (i >= hold - last_second) score_sum += c.score(to), ++scored;
  }
  t.succeeded = scored == 0 || score_sum / scored > o.performing_score;
  return t;
}

// How long `skill`'s own episode lasts from its first start under `seed` (at most `cap` seconds):
// a one-shot clip (a kick) ends its episode within a second or two.
double episode_seconds(const std::shared_ptr<const Skill>& skill, std::uint64_t seed, double cap) {
  Controller c({skill}, seed);
  const int most = static_cast<int>(std::lround(cap / c.control_dt()));
  int steps = 0;
  while (steps < most && !c.step().episode_over) ++steps;
  return steps * c.control_dt();
}

// `skill`'s mean value estimate of the states of its own first episode under `seed` (at most
// `cap` seconds): the scale of the value rule's threshold.
double mean_own_value(const std::shared_ptr<const Skill>& skill, std::uint64_t seed, double cap) {
  Controller c({skill}, seed);
  const int most = static_cast<int>(std::lround(cap / c.control_dt()));
  double sum = c.value(skill->name());
  int n = 1;
  for (int steps = 0; steps < most && !c.step().episode_over; ++steps, ++n) sum += c.value(skill->name());
  return sum / n;
}

}  // namespace

std::vector<TransitionCell> measure_transitions(const std::vector<std::shared_ptr<const Skill>>& skills, const TransitionOptions& o,
                                                const std::function<void(const TransitionCell&)>& progress) {
  if (skills.size() < 2) throw Error("transitions: two or more skills are needed");
  if (!o.score_rule && !o.value_baseline && !o.matching_baseline && !o.immediate_baseline) throw Error("transitions: no rule to measure");
  if (o.trials < 1 || !(o.latest_request >= o.earliest_request) || o.earliest_request < 0 || !(o.hold_seconds > 0))
    throw Error("transitions: trials >= 1, 0 <= earliest request <= latest request, and a hold > 0 s are needed");
  for (const auto& s : skills)
    if (s->discriminators().empty()) throw Error("transitions: skill '" + s->name() + "' has no discriminator to score with");
  std::vector<std::pair<std::string, double>> rules;
  for (const char* rule : {"score", "value", "matching"}) {
    const std::string r = rule;
    if ((r == "score" && !o.score_rule) || (r == "value" && !o.value_baseline) || (r == "matching" && !o.matching_baseline)) continue;
    for (double tau : o.thresholds) rules.emplace_back(rule, tau);
  }
  if (o.immediate_baseline) rules.emplace_back("immediately", 0.0);
  // The value rule's scale: each skill's mean value estimate over its own first episode.
  std::vector<double> own_value(skills.size(), 0.0);
  if (o.value_baseline)
    for (std::size_t j = 0; j < skills.size(); ++j) own_value[j] = mean_own_value(skills[j], o.seed, o.latest_request + 1.0);
  std::vector<TransitionCell> cells;
  for (std::size_t i = 0; i < skills.size(); ++i) {
    for (std::size_t j = 0; j < skills.size(); ++j) {
      if (i == j) continue;
      const auto& from = skills[i];
      const auto& to = skills[j];
      for (const auto& [rule, tau] : rules) {
        // Every rule of a pair meets the same trials: the same starts (the controller's seed) and
        // the same request times.
        const std::uint64_t pair_seed = o.seed * 1'000'003 + i * 1'009 + j;
        Controller c({from, to}, pair_seed);
        SwitchRule r;
        r.by = rule == "score" ? SwitchRule::By::Score
               : rule == "value" ? SwitchRule::By::Value
               : rule == "matching" ? SwitchRule::By::Matching
                                    : SwitchRule::By::Immediately;
        r.threshold = rule == "value" ? tau * own_value[j] : tau;
        r.time_limit_seconds = o.time_limit_seconds;
        c.set_switch_rule(r);
        std::mt19937_64 rng(pair_seed);
        // Requests come while the first skill performs: within its episode where that is short.
        const double lasts = episode_seconds(from, pair_seed, o.latest_request + 1.0);
        const double latest = std::min(o.latest_request, 0.8 * lasts), earliest = std::min(o.earliest_request, 0.4 * lasts);
        std::uniform_real_distribution<double> when(earliest, std::max(earliest, latest));
        TransitionCell cell{from->name(), to->name(), rule, tau};
        cell.value_threshold = rule == "value" ? r.threshold : 0.0;
        double waits = 0.0;
        for (int k = 0; k < o.trials; ++k) {
          Trial t;
          for (int attempt = 0; attempt < 5 && !t.valid; ++attempt)
            t = run_trial(c, from->name(), to->name(), static_cast<int>(std::lround(when(rng) / c.control_dt())), o);
          if (!t.valid) continue;
          ++cell.trials;
          cell.switched += t.switched, cell.succeeded += t.succeeded, cell.fell += t.fell;
          waits += t.wait;
        }
        cell.mean_wait = cell.switched ? waits / cell.switched : std::nan("");
        if (progress) progress(cell);
        cells.push_back(cell);
      }
    }
  }
  return cells;
}

}  // namespace mimic
