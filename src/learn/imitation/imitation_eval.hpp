#pragma once
// How closely a policy reproduces a reference clip, by the protocol of DESIGN.md section 5:
//   imitation error (seed 004 eq. 7): the mean over links of the distance between the simulated
//     and the reference link positions in the world, averaged over one motion cycle (the clip's
//     duration) from a start on the clip, over trials started at evenly spaced phases (i / n of
//     the clip); reported as mean and standard deviation over the trials, in metres.
//   normalised return (seed 003): each trial's full episode return (a fall ends it: nothing more
//     is earned) divided by the most its episode could earn (steps to the time limit or the
//     clip's end, times the environment's maximum reward per step); only where that maximum is known.
//   progress: the character's horizontal root displacement from the start to where its episode
//     ended (a fall ends it early), projected on the reference's over the full episode (to the time
//     limit or the clip's end), as a fraction of it (1: kept pace all along; 0.5: covered half the
//     ground); only for trials in which the reference moves at least kMinProgressMetres.
// A trial that falls keeps being measured to the end of its cycle: the character lies where it
// fell and its error grows, as the paper's error of a failed imitation does.
// Torch-free: the policy is any function from a stacked input to an action.
#include <functional>
#include <string>
#include <vector>

#include "env/character_env.hpp"

namespace mimic {

// Mean over links (joints) of |sim - ref| (metres). Throws Error when the link counts differ.
double link_position_error(const LinkFrames& sim, const LinkFrames& ref);
// Mean of link_position_error over the frames of two trajectories of equal length.
double trajectory_error(const std::vector<LinkFrames>& sim, const std::vector<LinkFrames>& ref);
// Per link (joint order): |sim - ref| in metres. Throws as link_position_error.
std::vector<double> link_distances(const LinkFrames& sim, const LinkFrames& ref);
// Posture without place: the mean over the links other than the root (joint 0) of
// |(sim_j - sim_root) - (ref_j - ref_root)|, the world error with the root's offset taken out (not
// its rotation: a turned torso still counts). A policy that lags or strays in the clip's posture
// scores near 0 here and high on link_position_error; a bent posture scores high on both.
// Throws Error with fewer than two links or differing counts.
double pose_error(const LinkFrames& sim, const LinkFrames& ref);
// Per link (joint order): |(sim_j - sim_root) - (ref_j - ref_root)|, 0 for the root; pose_error is
// mean_without_root of it. Throws as pose_error.
std::vector<double> pose_distances(const LinkFrames& sim, const LinkFrames& ref);
// The mean of a per-link vector over the links other than the root (index 0); throws with fewer than two.
double mean_without_root(const std::vector<double>& per_link);

// Consecutive frames a character must lie for to count as down (DESIGN.md section 5's robustness rule).
constexpr int kLyingFrames = 10;

// The reference's horizontal displacement below which progress is not measured (metres).
constexpr double kMinProgressMetres = 0.5;
// (sim . ref) / |ref|^2 on the horizontal parts of two displacements; NaN when the reference's is
// shorter than kMinProgressMetres.
double progress_along(const Vec3& sim_displacement, const Vec3& ref_displacement);

struct ImitationReport {
  std::vector<double> trial_errors;   // per trial: the error averaged over its cycle
  std::vector<double> trial_returns;  // per trial: normalised return (empty when not known)
  std::vector<double> trial_progress; // per trial whose reference moves: progress (above)
  std::vector<double> trial_pose_errors;  // per trial: pose_error averaged over its cycle
  // Per link (joint order; names in link_names): its distance averaged over each trial's cycle,
  // then over trials, so their mean over links is error_mean(). Says which links carry the error.
  std::vector<double> link_errors;
  // The same of pose_distances (root 0): mean_without_root of it is pose_error_mean(). Says which
  // links carry the posture's part (a run's arms, say) apart from the place's.
  std::vector<double> link_pose_errors;
  std::vector<std::string> link_names;
  // Per control step of the cycle (step 1 first): the error and the pose error at that step,
  // averaged over the trials that reach it. A start that goes wrong at once rises early; a
  // policy off the clip's pace drifts up along the cycle.
  std::vector<double> step_errors, step_pose_errors;
  int falls = 0;                      // trials whose episode ended in a fall (the env's termination rule)
  // Trials whose character lay on the ground in the full episode: a fall, or its root below half
  // the reference's root height for `kLyingFrames` consecutive frames. Catches a policy that lies
  // on its limbs with the torso off the ground, which a torso-contact rule does not end.
  int down = 0;
  double cycle_seconds = 0.0;
  double error_mean() const;
  double error_std() const;
  double normalised_return_mean() const;  // NaN when not known
  double progress_mean() const;           // NaN when the reference does not move
  double pose_error_mean() const;
  double pose_error_std() const;
};

// Runs `trials` episodes of `env` from the reference `clip` (the env's own reference when null)
// acting by `act` on inputs of `history` stacked frames. With `goal_along_clip`, a skill with a
// heading goal is commanded at every step the clip's direction of travel then
// (clip_travel_heading): it is measured walking the clip's own path, where otherwise its target
// stays where it faced at the start while a clip that curves (DeepMimic's walk turns 7 degrees a
// cycle) goes on turning. Throws Error without a clip, with a clip that does not fit the
// character, with trials < 1, or with goal_along_clip on an env without a heading goal.
using PolicyFunction = std::function<Eigen::VectorXd(const Eigen::VectorXd&)>;
ImitationReport measure_imitation(CharacterEnv& env, const PolicyFunction& act, int history, int trials, const Clip* clip = nullptr,
                                  bool goal_along_clip = false);

// The direction (yaw, radians) of the clip root's horizontal travel over one cycle centred on
// time t; where it travels less than 1 cm over that cycle, its root's heading at t.
double clip_travel_heading(const Clip& clip, double t);

// Robustness (seed 004 section 6.4, DESIGN.md section 5): control steps ("frames") a policy keeps
// the character up before it fails, failing meaning lying on the ground for `lying_frames`
// consecutive frames (a fall body touching the ground, or the root below half its standing
// height: lying on a pile of cubes counts); a fall does not end a trial (the character may get
// up). A trial ends at failure, at `max_frames`, or at the end of a non-cyclic reference. Trials start at
// evenly spaced phases of the env's reference clip (or from its own reset without one). The
// projectiles are the environment's (env: {projectiles: {enabled: true, mass: ...}}).
struct RobustnessReport {
  std::vector<double> frames;  // per trial: frames survived
  int max_frames = 0;
  double mean() const;
  double std() const;
};
RobustnessReport measure_robustness(CharacterEnv& env, const PolicyFunction& act, int history, int trials, int max_frames,
                                    int lying_frames = kLyingFrames, std::uint64_t seed = 1);

}  // namespace mimic
