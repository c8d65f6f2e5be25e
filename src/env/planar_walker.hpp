#pragma once
// The planar walker of seeds 000 (section 3.1) and 002 (section 3.1.1): OpenAI Gym's
// Walker2d-v2 rebuilt as generated MJCF. A torso and two legs of thigh, leg and foot (7 links)
// move in the x-z plane on a planar root (slide x, slide z, hinge y); 6 hinge motors (gear 100,
// ctrlrange -1..1) take the actions as joint torques.
//
// Task (seed 002 3.1.1, "taken directly from OpenAI Gym"): reward 1 (alive) + v_x (forward)
// - 1e-3 |u|^2 (control); the episode ends when the torso height leaves (0.8, 2.0) or, as in
// Gym's Walker2d, when |torso angle| >= 1 rad (the seed names only the height rule). Seed 000's
// walker instead rewards -|v_x - 5 m/s| (10 s episodes): a learner can build that from the
// "forward" term and control_dt().
#include <string>

#include "env/mjcf_env.hpp"

namespace mimic {

struct PlanarWalkerConfig {
  // Gym's Walker2d: 2 ms RK4 physics, 4 physics steps per action -> 8 ms, 125 Hz control.
  double timestep = 0.002;
  int frame_skip = 4;
  int max_steps = 1000;            // TimeLimit (Gym's max_episode_steps: 8 s of simulated time)
  double reset_noise = 0.005;      // uniform +-noise on every qpos and qvel entry at reset
  double velocity_clip = 10.0;     // observed qvel clipped to +-this (Gym)
  double min_height = 0.8, max_height = 2.0;  // torso height bounds (m)
  double max_angle = 1.0;          // torso pitch bound (rad)
  double control_weight = 1e-3;    // control term = -weight * |u|^2
};

// The walker's MJCF (local coordinates; `mimic character build` can write it out).
std::string planar_walker_mjcf(const PlanarWalkerConfig& cfg = {});

class PlanarWalkerEnv : public MjcfEnv {
 public:
  explicit PlanarWalkerEnv(const PlanarWalkerConfig& cfg = {});

  // qpos without root x (root z, root pitch, 6 joint angles) then clipped qvel (root vx, vz,
  // pitch rate, 6 joint rates): 17 values.
  int observation_size() const override { return 17; }
  std::vector<ObservationSlice> observation_layout() const override;
  Eigen::VectorXd reset(std::mt19937_64& rng) override;
  // Terms "alive", "forward" (root x displacement over the step / control_dt, as Gym computes
  // v_x), "control". Fall takes precedence over TimeLimit when both happen on the same step.
  StepResult step(const Eigen::VectorXd& action) override;

  const PlanarWalkerConfig& config() const { return cfg_; }
  Eigen::VectorXd observation() const;
  // The failure rule on the current state: Fall or None.
  Termination fall_check() const;
  double torso_height() const;
  double torso_angle() const;
  int steps() const { return steps_; }

 private:
  PlanarWalkerConfig cfg_;
  int steps_ = 0;
  bool started_ = false;
};

}  // namespace mimic
