#include "learn/imitation/imitation_eval.hpp"

#include <cmath>
#include <limits>
#include <numeric>

#include "core/error.hpp"
#include "core/statistics.hpp"
#include "env/down_rule.hpp"
#include "env/imitation_env.hpp"
#include "learn/imitation/frame_history.hpp"

namespace mimic {

std::vector<double> link_distances(const LinkFrames& sim, const LinkFrames& ref) {
  if (sim.joint_pos.size() != ref.joint_pos.size() || sim.joint_pos.empty())
    throw Error("imitation error: " + std::to_string(sim.joint_pos.size()) + " simulated links against " +
                std::to_string(ref.joint_pos.size()) + " reference links");
  std::vector<double> d(sim.joint_pos.size());
  for (std::size_t j = 0; j < d.size(); ++j) d[j] = (sim.joint_pos[j] - ref.joint_pos[j]).norm();
  return d;
}

double link_position_error(const LinkFrames& sim, const LinkFrames& ref) { return mean_of(link_distances(sim, ref)); }

double trajectory_error(const std::vector<LinkFrames>& sim, const std::vector<LinkFrames>& ref) {
  if (sim.size() != ref.size() || sim.empty())
    throw Error("imitation error: trajectories of " + std::to_string(sim.size()) + " and " + std::to_string(ref.size()) + " frames");
  double sum = 0;
  for (std::size_t f = 0; f < sim.size(); ++f) sum += link_position_error(sim[f], ref[f]);
  return sum / static_cast<double>(sim.size());
}

std::vector<double> pose_distances(const LinkFrames& sim, const LinkFrames& ref) {
  if (sim.joint_pos.size() != ref.joint_pos.size() || sim.joint_pos.size() < 2)
    throw Error("pose error: " + std::to_string(sim.joint_pos.size()) + " simulated links against " +
                std::to_string(ref.joint_pos.size()) + " reference links (needs two or more)");
  const Vec3 offset = sim.joint_pos[0] - ref.joint_pos[0];
  std::vector<double> d(sim.joint_pos.size(), 0.0);
  for (std::size_t j = 1; j < d.size(); ++j) d[j] = (sim.joint_pos[j] - ref.joint_pos[j] - offset).norm();
  return d;
}

double pose_error(const LinkFrames& sim, const LinkFrames& ref) { return mean_without_root(pose_distances(sim, ref)); }

double mean_without_root(const std::vector<double>& per_link) {
  if (per_link.size() < 2) throw Error("pose error: needs two or more links");
  return std::accumulate(per_link.begin() + 1, per_link.end(), 0.0) / static_cast<double>(per_link.size() - 1);
}

double ImitationReport::error_mean() const { return mean_of(trial_errors); }
double ImitationReport::error_std() const { return std_of(trial_errors); }
double RobustnessReport::mean() const { return mean_of(frames); }
double RobustnessReport::std() const { return std_of(frames); }

double ImitationReport::normalised_return_mean() const { return mean_of(trial_returns); }
double ImitationReport::progress_mean() const { return mean_of(trial_progress); }
double ImitationReport::pose_error_mean() const { return mean_of(trial_pose_errors); }
double ImitationReport::pose_error_std() const { return std_of(trial_pose_errors); }

double progress_along(const Vec3& sim_displacement, const Vec3& ref_displacement) {
  const Eigen::Vector2d sim = sim_displacement.head<2>(), ref = ref_displacement.head<2>();
  if (ref.norm() < kMinProgressMetres) return std::numeric_limits<double>::quiet_NaN();
  return sim.dot(ref) / ref.squaredNorm();
}

double clip_travel_heading(const Clip& clip, double t) {
  const double half = clip.duration() / 2;
  const Vec3 d = clip.sample(t + half).root_pos - clip.sample(t - half).root_pos;
  if (d.head<2>().norm() < 0.01) return heading_angle(clip.sample(t).rot[0]);
  return std::atan2(d.y(), d.x());
}

ImitationReport measure_imitation(CharacterEnv& env, const PolicyFunction& act, int history, int trials, const Clip* clip,
                                  bool goal_along_clip) {
  if (!clip) clip = env.reference();
  if (!clip) throw Error("imitation error: the environment has no reference clip; name one");
  if (goal_along_clip && !has_heading_goal(env))
    throw Error("imitation error: the goal along the clip is for a skill with a heading goal; this environment has none");
  // The target for the next action: the clip's direction of travel now (the observation's "goal"
  // part, seen from the character), in place of the env's own draw.
  int goal_at = -1;
  for (const ObservationSlice& part : env.observation_layout())
    if (part.name == "goal") goal_at = part.offset;
  const auto along_clip = [&](Eigen::VectorXd observation) {
    if (goal_along_clip) {
      set_goal_heading(env, clip_travel_heading(*clip, env.time()));
      observation.segment<2>(goal_at) = goal_observation(env);
    }
    return observation;
  };
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
  const std::size_t num_links = static_cast<std::size_t>(sk.num_joints());
  for (const Joint& j : sk.joints) report.link_names.push_back(j.name);
  report.link_errors.assign(num_links, 0.0);
  report.link_pose_errors.assign(num_links, 0.0);
  report.step_errors.assign(static_cast<std::size_t>(cycle_steps), 0.0);
  report.step_pose_errors.assign(static_cast<std::size_t>(cycle_steps), 0.0);
  std::vector<int> step_trials(static_cast<std::size_t>(cycle_steps), 0);
  FrameHistory frames(history);
  std::vector<LinkFrames> sim_frames, ref_frames;
  for (int i = 0; i < trials; ++i) {
    const double t0 = clip->duration() * i / trials;
    frames.reset(along_clip(env.reset(env.state_on_clip(*clip, t0))));
    // Progress: where the character's root is when its episode ends (a fall ends it early)
    // against where the reference's is at the full episode's end.
    const Vec3 sim_start = env.world().root_position(), ref_start = clip->sample(t0).root_pos;
    Vec3 sim_end = sim_start;
    // Steps of the full episode: to the time limit, or to a non-cyclic clip's end.
    const double episode_seconds = cyclic ? env.config().max_seconds : std::min(env.config().max_seconds, clip->duration() - t0);
    const int episode_steps = std::max(1, static_cast<int>(std::ceil(episode_seconds * hz - 1e-9)));
    const int error_steps = cyclic ? cycle_steps : std::min(cycle_steps, episode_steps);
    sim_frames.clear();
    ref_frames.clear();
    double ret = 0;
    bool over = false, fell = false;
    bool lay = false;
    int low = 0;  // consecutive frames with the root below half the reference's
    for (int t = 1; t <= std::max(error_steps, episode_steps); ++t) {
      if (over && t > error_steps) break;
      const StepResult r = env.step(act(frames.stacked()));
      frames.push(along_clip(r.observation));
      const Pose ref = clip->sample(env.time());
      if (t <= error_steps) {
        sim_frames.push_back(env.world().link_frames());
        ref_frames.push_back(forward_kinematics(clip->skeleton, ref));
      }
      // Drift is a training rule (the root strayed from the reference's), not part of the protocol:
      // the trial goes on through it, as it would without the rule; only falls end it.
      if (!over) {
        ret += r.reward();
        fell |= r.termination == Termination::Fall;
        over = r.done() && r.termination != Termination::Drift;
        sim_end = env.world().root_position();
        low = sim_end.z() < 0.5 * ref.root_pos.z() ? low + 1 : 0;
        lay |= low >= kLyingFrames;
      }
    }
    // Each frame's link distances once: the trial's error, its links' and its steps' come from them.
    const double frames_in_trial = static_cast<double>(sim_frames.size());
    double error = 0, pose = 0;
    for (std::size_t f = 0; f < sim_frames.size(); ++f) {
      const std::vector<double> d = link_distances(sim_frames[f], ref_frames[f]);
      const std::vector<double> dp = pose_distances(sim_frames[f], ref_frames[f]);
      const double frame_error = mean_of(d), posture = mean_without_root(dp);
      error += frame_error;
      pose += posture;
      report.step_errors[f] += frame_error;
      report.step_pose_errors[f] += posture;
      ++step_trials[f];
      for (std::size_t j = 0; j < num_links; ++j) {
        report.link_errors[j] += d[j] / (frames_in_trial * trials);
        report.link_pose_errors[j] += dp[j] / (frames_in_trial * trials);
      }
    }
    report.trial_errors.push_back(error / frames_in_trial);
    report.trial_pose_errors.push_back(pose / frames_in_trial);
    if (fell) ++report.falls;
    if (fell || lay) ++report.down;
    if (max_step > 0) report.trial_returns.push_back(ret / (episode_steps * max_step));
    const Vec3 ref_end = clip->sample(t0 + episode_steps / hz).root_pos;
    if (const double p = progress_along(sim_end - sim_start, ref_end - ref_start); std::isfinite(p)) report.trial_progress.push_back(p);
  }
  // Sums to means over the trials that reached each step; steps no trial reached are dropped.
  std::size_t reached = 0;
  while (reached < step_trials.size() && step_trials[reached] > 0) {
    report.step_errors[reached] /= step_trials[reached];
    report.step_pose_errors[reached] /= step_trials[reached];
    ++reached;
  }
  report.step_errors.resize(reached);
  report.step_pose_errors.resize(reached);
  return report;
}

RobustnessReport measure_robustness(CharacterEnv& env, const PolicyFunction& act, int history, int trials, int max_frames,
                                    int lying_frames, std::uint64_t seed) {
  if (trials < 1 || max_frames < 1 || lying_frames < 1) throw Error("robustness: trials, frames and lying frames must be at least 1");
  const Clip* clip = env.reference();
  RobustnessReport report;
  report.max_frames = max_frames;
  FrameHistory frames(history);
  std::mt19937_64 rng(seed);
  for (int i = 0; i < trials; ++i) {
    frames.reset(clip ? env.reset(env.state_on_clip(*clip, clip->duration() * i / trials)) : env.reset(rng));
    if (ProjectileLauncher* launcher = env.projectiles()) launcher->reseed(seed * 1000003 + static_cast<std::uint64_t>(i));
    // Down: a fall body on the ground, or the root below half its standing height (lying on cubes).
    DownRule rule(env.world().character().rest_root_height(), 0.5, lying_frames);
    int survived = max_frames;
    for (int t = 1; t <= max_frames; ++t) {
      const StepResult r = env.step(act(frames.stacked()));
      frames.push(r.observation);
      if (rule.update(env.world().root_position().z(), env.fall_contact())) {
        survived = t - lying_frames;  // the frames before it went down for good
        break;
      }
      if (r.termination == Termination::ClipEnd || r.termination == Termination::TimeLimit) {
        survived = t;
        break;
      }
    }
    report.frames.push_back(survived);
  }
  return report;
}

}  // namespace mimic
