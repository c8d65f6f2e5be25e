#pragma once
// The imitation environment: a character on a plane whose episodes start from poses of one or
// more clips (seed 004's integrated learning) and whose reward comes from outside (a
// discriminator) unless a task adds one. Nothing is tracked: the clips supply starts (and a
// non-cyclic clip's end), not a phase. The optional task terms, per control step, are seed 000's
// "move forward" task (Merel et al. 2017, Figure 4 and supplement), placed at the origin and
// rewarded for moving along the track (world +X):
//   alive    alive_bonus: the baseline for not having fallen
//   forward  forward_weight * v_x, v_x the root's mean velocity along +X over the step (its X
//            displacement / control dt: the instantaneous velocity of a gait is noisy); with
//            target_speed > 0 the paper's other variant, -forward_weight * |v_x - target_speed|
//   lateral  -lateral_weight * |y|: the root's distance from the track's centre line y = 0
//   control  -control_weight * |a|^2 on the action as the environment reads it (clipped to +-pi,
//            NaN as 0)
// or seed 004 eq. 8's heading goal (below). Seed 000's experiment is the start of an episode:
// motion-capture poses (a random time on a clip) versus a fixed engineered pose, both with a
// little noise on the joints. Config name `imitation` (`humanoid_forward` is the same, the name
// older models were saved with).
#include <memory>
#include <string>
#include <vector>

#include "env/character_env.hpp"

namespace mimic {

struct ImitationEnvConfig {
  enum class Init {
    FixedPose,  // the character's rest pose standing at rest: the engineered start
    Mocap,      // the pose and velocities at a uniformly random time on the clip (to its end if it does not loop)
  };
  Init init = Init::Mocap;
  // The character environment: its observation (by default proprioception, as the paper's RL runs:
  // joint angles and velocities, root velocity, velocimeter, gyro, uprightness, end effectors; no
  // phase, nothing is tracked; mocap starts fill a "links" history with the clip's poses before the
  // start), falls, 10 s episodes, terrain, pushes and projectiles. Its max_drift (> 0) measures the
  // root against the clip a start was drawn from, played on from the start time and placed as the
  // start was, so it needs mocap starts: a policy that stands in a punch's guard while the clip
  // steps forward otherwise earns the full episode (a state-only discriminator has no phase to tell
  // the guard from the clip's first frames). Empty fall_links: the character's own (DeepMimic's
  // root, chest and neck), which lets a policy sit on its thighs and shuffle; seed 004 §5.2 ends a
  // walk at any contact but the feet's.
  CharacterEnvConfig env = defaults();
  double alive_bonus = 1.0;
  double forward_weight = 1.0;   // per m/s
  double target_speed = 0.0;     // m/s; 0: as fast as possible
  double lateral_weight = 0.1;   // per m off the centre line
  double control_weight = 1e-3;  // per rad^2 of axis-angle PD targets (28 values for humanoid3d)
  double init_noise = 0.02;      // rad: uniform +- on each joint axis at every start
  // Fallen starts (a get-up's): this fraction of episodes starts lying where the character fell.
  // The episode's ordinary start is turned to a random orientation 1.2 m up and dropped limp (no
  // joint torques) for 1.5 s; it starts from where it settled, and contacts that would end an
  // episode as a fall do not end this one (it has fallen already): the policy learns to get up
  // from how a character lands, not only from the clip's own poses. CharacterEnv::lying_start()
  // tells such an episode.
  double fallen_starts = 0.0;
  // Starts from other motion (switching between skills: a skill trained only from its own clips
  // has never seen the states another skill hands it). This share of Mocap episodes starts at a
  // time drawn from the start clips given to make_imitation_env (another skill's clips) instead
  // of its own: Bergamin et al. 2019's transition starts; seed 004 §5.3 perturbs starts for the
  // same end. Such an episode follows no clip (no drift is measured) and, where the skill's own
  // clips do not loop, lasts one whole clip of its own (the one the ordinary draw chose).
  double start_clip_share = 0.0;
  // Seed 004 eq. 8's example of a dynamic goal: a target heading, drawn at every start and every
  // goal_period seconds, uniformly within goal_turn degrees of the character's heading at the draw
  // (180: any direction; a steering command turns by less; 0: straight on, the plain walk). With Goal::Heading the forward and lateral terms give way to
  //   goal   goal_weight * ((1 - goal_facing) * moving + goal_facing * max(0, f . d)), where
  //          moving = exp(-goal_sharpness (max(0, goal_speed - d . v)^2 + 0.1 |v - (d . v) d|^2))
  //          while d . v > 0, else 0; d the target direction, v the root's mean horizontal
  //          velocity over the step, f the direction the character faces. The form is ASE's
  //          heading reward (Peng et al. 2022: the speed along the target, a tenth of the speed
  //          across it, and 0.3 for facing it); the miss is one-sided as DeepMimic's (Peng et al.
  //          2018: no penalty for going faster) and the sharpness DeepMimic's 2.5. Without the
  //          across and facing parts a walker met targets 45 degrees off by walking faster.
  // and the observation gains "goal": cos and sin of the target direction in the heading frame.
  enum class Goal { None, Heading };
  Goal goal = Goal::None;
  double goal_speed = 1.0;   // m/s along the target direction
  double goal_period = 4.0;  // s between targets
  double goal_weight = 1.0;
  double goal_sharpness = 2.5;  // 1 / (m/s)^2
  double goal_facing = 0.3;     // the share of the goal reward for facing the target
  double goal_turn = 180.0;  // degrees, in [0, 180]

  static CharacterEnvConfig defaults() {
    CharacterEnvConfig c;
    c.observations.names = {"full_state", "egocentric"};
    c.max_seconds = 10.0;
    return c;
  }
};

// The task's environment (actions: axis-angle PD targets). `clip` gives Mocap's starts and must
// fit `ch`; FixedPose ignores it (it may be null). A Mocap start on a non-cyclic clip (kick, punch)
// ends its episode where the clip ends (ClipEnd, not a failure; seed 004 §5.2), a cyclic clip's at
// max_seconds. Throws Error on a missing or unfitting clip or a negative weight, noise or speed;
// KeyError on env.max_drift without mocap starts.
std::unique_ptr<CharacterEnv> make_imitation_env(const CharacterModel& ch, std::shared_ptr<const Clip> clip,
                                                const ImitationEnvConfig& cfg = {});
// Mocap starts from several clips (seed 004's integrated learning): a start time uniform over
// all their frames together, so each clip starts in proportion to its duration. Each clip is a
// start group (CharacterEnv::choose_start_group): choosing clip i starts from it alone.
// `start_clips`: the other motion of cfg.start_clip_share (each must fit `ch`; needed when the
// share is above 0).
std::unique_ptr<CharacterEnv> make_imitation_env(const CharacterModel& ch, std::vector<std::shared_ptr<const Clip>> clips,
                                                const ImitationEnvConfig& cfg = {},
                                                std::vector<std::shared_ptr<const Clip>> start_clips = {});

// The target direction (world yaw, radians) of a Goal::Heading env; tests and tools set it
// (it holds until the next start or the next goal_period). Error for an env without that goal.
double goal_heading(const CharacterEnv& env);
void set_goal_heading(CharacterEnv& env, double yaw);
bool has_heading_goal(const CharacterEnv& env);
// The observation's "goal" part for the target now: its cos and sin in the character's heading frame.
Eigen::Vector2d goal_observation(const CharacterEnv& env);

// `s` moved to the start of the track: root over the origin facing +X, its height kept, its
// velocities, past poses and source clip's placement turned with it.
InitState place_at_track_start(InitState s);

}  // namespace mimic
