#include "learn/imitation/crossing_eval.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "core/error.hpp"
#include "env/imitation_env.hpp"
#include "learn/imitation/frame_history.hpp"

namespace mimic {

CrossingTrial::CrossingTrial(double finish_x, double standing_height) : finish_(finish_x), rule_(standing_height, 0.5, kLyingFrames) {}

bool CrossingTrial::update(double root_x, double height_above_ground, bool fall_contact, bool failed) {
  if (crossed_ || down_) return true;
  ++steps_;
  farthest_ = std::max(farthest_, root_x);
  down_ = rule_.update(height_above_ground, fall_contact) || failed;
  crossed_ = !down_ && root_x >= finish_;
  return crossed_ || down_;
}

CrossingReport measure_crossing(CharacterEnv& env, const PolicyFunction& act, int history, const CrossingOptions& o) {
  if (o.trials < 1 || !(o.seconds > 0) || !(o.margin >= 0) || !std::isfinite(o.seconds) || !std::isfinite(o.margin))
    throw Error("crossing: trials >= 1, a positive trial length and a non-negative margin");
  const Terrain& terrain = env.terrain();
  CrossingReport report;
  report.finish_x = terrain.course_end() + o.margin;  // Error for flat ground
  const double hz = env.config().sim.control_hz;
  const int steps = std::max(1, static_cast<int>(std::lround(o.seconds * hz)));
  report.seconds = steps / hz, report.trials = o.trials;
  const bool steered = has_heading_goal(env);
  const double standing = env.world().character().rest_root_height();
  std::mt19937_64 rng(o.seed);
  FrameHistory frames(history);
  for (int i = 0; i < o.trials; ++i) {
    frames.reset(env.reset(rng));
    if (steered) set_goal_heading(env, 0.0);  // along the course (again at every step: the env's own redraws do not count)
    CrossingTrial trial(report.finish_x, standing);
    bool decided = false;
    for (int t = 1; t <= steps && !decided; ++t) {
      if (steered && t > 1) set_goal_heading(env, 0.0);
      const StepResult r = env.step(act(frames.stacked()));
      frames.push(r.observation);
      const Vec3 root = env.world().root_position();
      decided = trial.update(root.x(), root.z() - terrain.height(root.x(), root.y()), env.fall_contact(), is_failure(r.termination));
      if (!decided && r.termination != Termination::None && t < steps)
        throw Error("crossing: the episode ended after " + std::to_string(t) + " steps (" + to_string(r.termination) +
                    "); give the environment longer episodes (env.max_seconds)");
    }
    if (trial.crossed()) {
      ++report.crossed;
      report.seconds_to_cross.push_back(trial.steps() / hz);
    } else if (trial.down()) {
      ++report.falls;
    }
    report.progress.push_back(std::clamp(trial.farthest_x() / report.finish_x, 0.0, 1.0));
  }
  return report;
}

}  // namespace mimic
