#pragma once
// Motion tracking (seed 003 section 7.2, the DeepMimic objective): the character follows a
// reference clip at the current phase and is rewarded, per control step, by
//   r = 0.65 r_pose + 0.10 r_velocity + 0.15 r_end_effector + 0.10 r_com,   each in [0, 1]:
//   r_pose         exp(-2   * mean_j angle(q*_j ^-1 q_j)^2)    joint rotations, the root's in the world
//   r_velocity     exp(-0.1 * mean_j |w*_j - w_j|^2)           joint angular velocities (own frames)
//   r_end_effector exp(-40  * mean_e |p*_e - p_e|^2)           hands and feet relative to the root,
//                                                               each in its own heading frame
//   r_com          exp(-10  * |c* - c|^2)                       centre of mass in the world
// or, with com_term velocity, exp(-scale * |v*_c - v_c|^2) on the centre of mass's mean velocity
// over the step (DeepMimic's implementation; its scale is 10 * 0.1 = 1): a position kernel gives
// no pull once the character has fallen a metre behind a fast clip (the dog's 2.4 m/s trot).
// An optional fifth term, weighted 0 unless set (DeepMimic's SceneImitate.cpp, weight 0.2 there):
//   r_root         exp(-5 * (|p*_r - p_r|^2 + 0.1 angle(q*_r^-1 q_r)^2 + 0.01 |v*_r - v_r|^2
//                            + 0.001 |w*_r - w_r|^2))        the root's world position (height above
//                                                            the ground), rotation and velocities
// and, with resync_root, the reference moved horizontally onto the character's root at every new
// cycle of a looping clip (DeepMimic's sync_char_root_pos): the positional terms then measure this
// cycle's path from where the character is, not a lag that only grows.
// Means, not the paper's sums: DeepMimic's implementation (which seed 003 builds on) normalises its
// joint weights to sum 1 and divides the end-effector error by their count; with sums the kernels
// of a 13-joint humanoid would be near zero for any early policy. A step's reward is at most 1, so
// an episode's normalised return (SFV) is its return divided by its step count at full length.
// Reference velocities are finite differences of the clip. The clip sets the episode: a
// non-cyclic one ends it at its end; a cyclic one goes on (root drift and heading change per
// cycle carried by Clip::sample) until max_seconds.
#include <memory>

#include "env/character_env.hpp"

namespace mimic {

struct TrackingWeights {
  double pose = 0.65, velocity = 0.10, end_effector = 0.15, com = 0.10, root = 0.0;
};
struct TrackingScales {
  double pose = 2.0, velocity = 0.1, end_effector = 40.0, com = 10.0, root = 5.0;
};

// What the reward compares, of the simulated character or of the reference at one instant.
struct TrackedState {
  Pose pose;
  PoseVelocity velocity;
  LinkFrames links;
  Vec3 com = Vec3::Zero();
  Vec3 com_velocity = Vec3::Zero();  // mean over the last control step
};

enum class ComTerm { Position, Velocity };

// The five kernels, each in [0, 1] (1: identical).
struct TrackingTerms {
  double pose = 1, velocity = 1, end_effector = 1, com = 1, root = 1;
};
TrackingTerms tracking_terms(const Skeleton& sk, const TrackedState& sim, const TrackedState& ref, const TrackingScales& scales = {},
                             ComTerm com = ComTerm::Position);

// The character's masses, to place the reference's centre of mass from its link frames.
class MassModel {
 public:
  explicit MassModel(const World& world);
  Vec3 centre_of_mass(const LinkFrames& links) const;

 private:
  std::vector<double> mass_;     // per joint (its body)
  std::vector<Vec3> local_com_;  // body centre of mass in the joint's frame
  double total_ = 0.0;
};

// The reference's state at clip time t; with dt > 0 also its centre of mass's mean velocity
// over [t - dt, t].
TrackedState reference_state(const Clip& clip, const MassModel& masses, double t, double dt = 0.0);

struct TrackingConfig {
  enum class Init {
    Fixed,      // FSI: the clip's first frame
    Reference,  // RSI: a uniformly random time on the clip
  };
  Init init = Init::Reference;
  TrackingWeights weights;
  TrackingScales scales;
  ComTerm com_term = ComTerm::Position;  // Velocity: set scales.com to about 1
  bool resync_root = false;              // the reference onto the character at each new cycle
  // The character environment: the policy sees its state and the clip's phase; episodes last 20 s
  // on a cyclic clip (a non-cyclic clip ends at its end) and end early on a fall or with the root
  // below half the reference's height; early_termination off for contact-rich clips (roll, get-up).
  CharacterEnvConfig env = defaults();

  static CharacterEnvConfig defaults() {
    CharacterEnvConfig c;
    c.observations.names = {"full_state", "phase"};
    c.fall_height = 0.5;
    c.max_seconds = 20.0;
    return c;
  }
};

// The environment; reward terms are named pose, velocity, end_effector and com (weighted), and
// root where its weight is above 0.
// Throws Error on a clip that does not fit the character, a negative weight or scale.
std::unique_ptr<CharacterEnv> make_tracking_env(const CharacterModel& ch, std::shared_ptr<const Clip> clip,
                                                const TrackingConfig& cfg = {});

}  // namespace mimic
