#include "learn/imitation/steering_eval.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <random>

#include "core/error.hpp"
#include "env/down_rule.hpp"
#include "env/imitation_env.hpp"
#include "learn/imitation/frame_history.hpp"

namespace mimic {

double heading_error_degrees(const Vec3& travel, double target_yaw) {
  if (travel.head<2>().norm() < 1e-9) return 180.0;
  return std::abs(std::remainder(std::atan2(travel.y(), travel.x()) - target_yaw, 2 * kPi)) * 180.0 / kPi;
}

double SteeringReport::success_rate() const {
  if (trials == 0) return std::nan("");
  const auto within = std::count_if(error_degrees.begin(), error_degrees.end(), [this](double e) { return e <= tolerance_degrees; });
  return static_cast<double>(within) / trials;
}

SteeringReport measure_steering(CharacterEnv& env, const PolicyFunction& act, int history, const SteeringOptions& o) {
  (void)goal_heading(env);  // throws for an environment without a heading goal
  if (o.trials < 1 || !(o.turn_degrees >= 0 && o.turn_degrees <= 180) || !(o.settle_seconds >= o.travel_seconds) || !(o.hold_seconds > 0) ||
      !(o.travel_seconds > 0) || !(o.respond_seconds > 0 && o.respond_seconds <= o.hold_seconds) || !(o.tolerance_degrees > 0))
    throw Error("steering: trials >= 1, a turn in [0, 180] degrees, settle >= travel > 0, 0 < respond <= hold and a positive tolerance");
  const double hz = env.config().sim.control_hz;
  const auto steps = [hz](double seconds) { return std::max(1, static_cast<int>(std::lround(seconds * hz))); };
  const int settle = steps(o.settle_seconds), hold = steps(o.hold_seconds), travel = steps(o.travel_seconds), respond = steps(o.respond_seconds);
  constexpr double kDegrees = 180.0 / kPi;
  SteeringReport report;
  report.turn_degrees = o.turn_degrees, report.respond_seconds = respond / hz, report.tolerance_degrees = o.tolerance_degrees;
  report.trials = o.trials;
  std::mt19937_64 rng(o.seed);
  FrameHistory frames(history);
  for (int i = 0; i < o.trials; ++i) {
    frames.reset(env.reset(rng));
    set_goal_heading(env, heading_angle(env.world().pose().rot[0]));  // straight on while it settles
    DownRule down(env.world().character().rest_root_height(), 0.5, kLyingFrames);
    std::deque<Vec3> roots{env.world().root_position()};  // the last travel + 1 root positions
    bool fell = false;
    double target = 0, error_at_respond = std::nan(""), first_within = std::nan(""), along = 0;
    for (int t = 1; t <= settle + hold && !fell; ++t) {
      if (t == settle + 1) {  // the command: a turn from where the character faces now
        const double sign = i % 2 == 0 ? 1.0 : -1.0;
        target = heading_angle(env.world().pose().rot[0]) + sign * o.turn_degrees / kDegrees;
        set_goal_heading(env, std::remainder(target, 2 * kPi));
      }
      const StepResult r = env.step(act(frames.stacked()));
      frames.push(r.observation);
      roots.push_back(env.world().root_position());
      if (static_cast<int>(roots.size()) > travel + 1) roots.pop_front();
      fell = down.update(env.world().root_position().z(), env.fall_contact()) || is_failure(r.termination);
      if (!fell && r.termination != Termination::None && t < settle + hold)  // a time limit or a clip's end cut the trial short
        throw Error("steering: the episode ended after " + std::to_string(t) + " steps (" + to_string(r.termination) +
                    "); give the environment longer episodes (env.max_seconds)");
      if (fell || t <= settle) continue;
      const Vec3 d = roots.back() - roots.front();
      const double error = heading_error_degrees(d, target);
      const int since = t - settle;
      if (std::isnan(first_within) && error <= o.tolerance_degrees) first_within = since / hz;
      if (since == respond) error_at_respond = error;
      if (since > hold / 2) along += (std::cos(target) * d.x() + std::sin(target) * d.y()) / (static_cast<double>(roots.size() - 1) / hz);
    }
    if (fell) {
      ++report.falls;
      continue;
    }
    report.error_degrees.push_back(error_at_respond);
    report.seconds_to_tolerance.push_back(std::isnan(first_within) ? std::numeric_limits<double>::infinity() : first_within);
    report.speed_along.push_back(along / (hold - hold / 2));
  }
  return report;
}

}  // namespace mimic
