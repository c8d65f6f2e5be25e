#include "learn/imitation/context_switch.hpp"

#include <mujoco/mujoco.h>

#include <string>

#include "core/error.hpp"
#include "learn/imitation/frame_history.hpp"

namespace mimic {

namespace {

// The root body's horizontal position (MuJoCo body 1: the first body under the world).
Eigen::Vector2d root_xy(const mjData* d) { return Eigen::Vector2d(d->xpos[3], d->xpos[4]); }

}  // namespace

SwitchReport measure_switch(ContextEnv& env, const StackedPolicy& act, int history, int from, int to, int trials, int hold_steps,
                            std::uint64_t seed) {
  const std::string what = "context switch " + std::to_string(from) + " -> " + std::to_string(to);
  if (from < 0 || to < 0 || from >= env.contexts() || to >= env.contexts())
    throw Error(what + ": the environment has contexts 0 to " + std::to_string(env.contexts() - 1));
  if (from == to) throw Error(what + ": the two contexts must differ");
  if (hold_steps < 2) throw Error(what + ": each hold needs at least 2 steps, got " + std::to_string(hold_steps));
  if (trials < 1) throw Error(what + ": needs at least one trial");
  const mjData* data = env.physics_data();
  if (!data || !env.physics_model() || env.physics_model()->nbody < 2) throw Error(what + ": the environment has no simulated body to measure");

  // Whatever happens, the env goes back to drawing its own contexts.
  struct Release {
    ContextEnv& env;
    ~Release() { env.release_context(); }
  } release{env};
  SwitchReport report;
  report.from = from, report.to = to, report.hold_steps = hold_steps, report.trials = trials;
  std::mt19937_64 rng(seed);
  FrameHistory frames(history);
  for (int trial = 0; trial < trials; ++trial) {
    env.hold_context(from);
    frames.reset(env.reset(rng));
    bool fell = false;
    for (int phase = 0; phase < 2 && !fell; ++phase) {
      if (phase == 1) env.hold_context(to);  // the observation shows it from the next step on
      const double t_start = data->time;
      Eigen::Vector2d mid_xy = root_xy(data);
      double mid_time = t_start;
      for (int t = 1; t <= hold_steps; ++t) {
        const StepResult r = env.step(act(frames.stacked()));
        frames.push(r.observation);
        if (trial == 0 && phase == 0 && t == 1) report.hold_seconds = hold_steps * (data->time - t_start);
        if (t == hold_steps / 2) mid_xy = root_xy(data), mid_time = data->time;
        if (is_failure(r.termination)) {
          fell = true;
          ++(phase == 0 ? report.fell_before : report.fell_after);
          break;
        }
        if (r.done() && !(phase == 1 && t == hold_steps))
          throw Error(what + ": an episode ended (" + std::string(to_string(r.termination)) + ") after " +
                      std::to_string(phase * hold_steps + t) + " steps, before the trial's " + std::to_string(2 * hold_steps) +
                      "; shorten the holds");
      }
      if (fell) break;
      const double speed = (root_xy(data) - mid_xy).norm() / (data->time - mid_time);
      (phase == 0 ? report.speed_before : report.speed_after).push_back(speed);
    }
  }
  return report;
}

}  // namespace mimic
