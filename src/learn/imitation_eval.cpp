#include "learn/imitation_eval.hpp"

#include <cmath>
#include <limits>
#include <numeric>

#include "core/error.hpp"
#include "learn/frame_history.hpp"

namespace mimic {

double link_position_error(const LinkFrames& sim, const LinkFrames& ref) {
  if (sim.joint_pos.size() != ref.joint_pos.size() || sim.joint_pos.empty())
    throw Error("imitation error: " + std::to_string(sim.joint_pos.size()) + " simulated links against " +
                std::to_string(ref.joint_pos.size()) + " reference links");
  double sum = 0;
  for (std::size_t j = 0; j < sim.joint_pos.size(); ++j) sum += (sim.joint_pos[j] - ref.joint_pos[j]).norm();
  return sum / static_cast<double>(sim.joint_pos.size());
}

double trajectory_error(const std::vector<LinkFrames>& sim, const std::vector<LinkFrames>& ref) {
  if (sim.size() != ref.size() || sim.empty())
    throw Error("imitation error: trajectories of " + std::to_string(sim.size()) + " and " + std::to_string(ref.size()) + " frames");
  double sum = 0;
  for (std::size_t f = 0; f < sim.size(); ++f) sum += link_position_error(sim[f], ref[f]);
  return sum / static_cast<double>(sim.size());
}

namespace {

double mean_of(const std::vector<double>& v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  return std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}

}  // namespace

double ImitationReport::error_mean() const { return mean_of(trial_errors); }

double ImitationReport::error_std() const {
  if (trial_errors.empty()) return std::numeric_limits<double>::quiet_NaN();
  const double m = error_mean();
  double ss = 0;
  for (double e : trial_errors) ss += (e - m) * (e - m);
  return std::sqrt(ss / static_cast<double>(trial_errors.size()));
}

double ImitationReport::normalised_return_mean() const { return mean_of(trial_returns); }

ImitationReport measure_imitation(CharacterEnv& env, const PolicyFunction& act, int history, int trials, const Clip* clip) {
  if (!clip) clip = env.reference();
  if (!clip) throw Error("imitation error: the environment has no reference clip; name one");
  const Skeleton& sk = env.world().character().skeleton;
  if (clip->skeleton.num_joints() != sk.num_joints())
    throw Error("imitation error: clip '" + clip->name + "' does not fit character '" + env.world().character().name + "'");
  if (trials < 1) throw Error("imitation error: needs at least one trial");
  const double hz = env.config().sim.control_hz;
  const bool cyclic = clip->loop == LoopMode::Wrap;
  const int cycle_steps = std::max(1, static_cast<int>(std::lround(clip->duration() * hz)));
  const double max_step = env.max_step_reward();

  ImitationReport report;
  report.cycle_seconds = cycle_steps / hz;
  FrameHistory frames(history);
  std::vector<LinkFrames> sim_frames, ref_frames;
  for (int i = 0; i < trials; ++i) {
    const double t0 = clip->duration() * i / trials;
    frames.reset(env.reset(init_state_from_clip(*clip, t0)));
    // Steps of the full episode: to the time limit, or to a non-cyclic clip's end.
    const double episode_seconds = cyclic ? env.config().max_seconds : std::min(env.config().max_seconds, clip->duration() - t0);
    const int episode_steps = std::max(1, static_cast<int>(std::ceil(episode_seconds * hz - 1e-9)));
    const int error_steps = cyclic ? cycle_steps : std::min(cycle_steps, episode_steps);
    sim_frames.clear();
    ref_frames.clear();
    double ret = 0;
    bool over = false, fell = false;
    for (int t = 1; t <= std::max(error_steps, episode_steps); ++t) {
      if (over && t > error_steps) break;
      const StepResult r = env.step(act(frames.stacked()));
      frames.push(r.observation);
      if (t <= error_steps) {
        sim_frames.push_back(env.world().link_frames());
        ref_frames.push_back(forward_kinematics(clip->skeleton, clip->sample(env.time())));
      }
      if (!over) {
        ret += r.reward();
        fell |= is_failure(r.termination);
        over = r.done();
      }
    }
    report.trial_errors.push_back(trajectory_error(sim_frames, ref_frames));
    if (fell) ++report.falls;
    if (max_step > 0) report.trial_returns.push_back(ret / (episode_steps * max_step));
  }
  return report;
}

}  // namespace mimic
