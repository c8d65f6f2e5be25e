#pragma once
// Seed 000's "move forward" RL task (Merel et al. 2017, Figure 4 and supplement): the humanoid
// on a plane, placed at the origin, rewarded for moving along the track (world +X); 10 s episodes
// that a fall ends early. Reward terms, per control step:
//   alive    alive_bonus: the baseline for not having fallen
//   forward  forward_weight * v_x, v_x the root's mean velocity along +X over the step (its X
//            displacement / control dt: the instantaneous velocity of a gait is noisy); with
//            target_speed > 0 the paper's other variant, -forward_weight * |v_x - target_speed|
//   lateral  -lateral_weight * |y|: the root's distance from the track's centre line y = 0
//   control  -control_weight * |a|^2 on the action as the environment reads it (clipped to +-pi,
//            NaN as 0)
// The experiment is the start of an episode: motion-capture poses (a random time on a clip) versus
// a fixed engineered pose, both with a little noise on the joints.
#include <memory>
#include <string>
#include <vector>

#include "env/character_env.hpp"

namespace mimic {

struct HumanoidForwardConfig {
  enum class Init {
    FixedPose,  // the character's rest pose standing at rest: the engineered start
    Mocap,      // the pose and velocities at a uniformly random time on the clip (to its end if it does not loop)
  };
  Init init = Init::Mocap;
  double max_seconds = 10.0;  // TimeLimit
  double alive_bonus = 1.0;
  double forward_weight = 1.0;   // per m/s
  double target_speed = 0.0;     // m/s; 0: as fast as possible
  double lateral_weight = 0.1;   // per m off the centre line
  double control_weight = 1e-3;  // per rad^2 of axis-angle PD targets (28 values for humanoid3d)
  double init_noise = 0.02;      // rad: uniform +- on each joint axis at every start
  // Bodies whose ground contact is a fall. Empty: the character's own (DeepMimic's root, chest and
  // neck), which lets a policy sit on its thighs and shuffle; seed 004 §5.2 ends a walk at any
  // contact but the feet's.
  std::vector<std::string> fall_links;
  // > 0: an episode also ends, as a failure (Drift), once the root is more than this many metres
  // (horizontally) from the root of the clip its start was drawn from, played on from the start
  // time and placed as the start was. Mocap starts only. A policy that stands in a punch's guard
  // while the clip steps forward otherwise earns the full episode: a state-only discriminator has no
  // phase to tell the guard from the clip's first frames.
  double max_drift = 0.0;
  // The policy's input: proprioception, as the paper's RL runs (joint angles and velocities, root
  // velocity, velocimeter, gyro, uprightness, end effectors). No phase: nothing is tracked.
  // Mocap starts fill a "links" history with the clip's poses before the start.
  ObservationConfig observations{.names = {"full_state", "egocentric"}};
  ProjectileSpec projectiles;  // seed 004's robustness test when enabled (mimic eval --robustness)
  PdLimit pd_limit = PdLimit::Spring;  // what the joints' torque limits bound (sim/world.hpp)
  bool lift_starts = false;            // raise starts out of the floor (CharacterEnvConfig)
  StartMomentumSmoothing start_momentum;  // window > 0 smooths mocap starts' momentum (CharacterEnvConfig)
  // Seed 004 eq. 8's example of a dynamic goal: a target heading, drawn uniformly at every start
  // and every goal_period seconds. With Goal::Heading the forward and lateral terms give way to
  //   goal   goal_weight * exp(-0.25 (goal_speed - d . v)^2), d the target direction, v the root's
  //          mean horizontal velocity over the step
  // and the observation gains "goal": cos and sin of the target direction in the heading frame.
  enum class Goal { None, Heading };
  Goal goal = Goal::None;
  double goal_speed = 1.0;   // m/s along the target direction
  double goal_period = 4.0;  // s between targets
  double goal_weight = 1.0;
};

// The task's environment (actions: axis-angle PD targets). `clip` gives Mocap's starts and must
// fit `ch`; FixedPose ignores it (it may be null). A Mocap start on a non-cyclic clip (kick, punch)
// ends its episode where the clip ends (ClipEnd, not a failure; seed 004 §5.2), a cyclic clip's at
// max_seconds. Throws Error on a missing or unfitting clip or a negative weight, noise or speed.
std::unique_ptr<CharacterEnv> make_humanoid_forward_env(const CharacterModel& ch,
                                                        std::shared_ptr<const Clip> clip,
                                                        const HumanoidForwardConfig& cfg = {});
// Mocap starts from several clips (seed 004's integrated learning): a start time uniform over
// all their frames together, so each clip starts in proportion to its duration. Each clip is a
// start group (CharacterEnv::choose_start_group): choosing clip i starts from it alone.
std::unique_ptr<CharacterEnv> make_humanoid_forward_env(const CharacterModel& ch,
                                                        std::vector<std::shared_ptr<const Clip>> clips,
                                                        const HumanoidForwardConfig& cfg = {});

// The target direction (world yaw, radians) of a Goal::Heading env; tests and tools set it
// (it holds until the next start or the next goal_period). Error for an env without that goal.
double goal_heading(const CharacterEnv& env);
void set_goal_heading(CharacterEnv& env, double yaw);

// `s` moved to the start of the track: root over the origin facing +X, its height kept, its
// velocities, past poses and source clip's placement turned with it.
InitState place_at_track_start(InitState s);

}  // namespace mimic
