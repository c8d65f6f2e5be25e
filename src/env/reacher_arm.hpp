#pragma once
// The planar arms of seed 000's validation (section 3.1, supplement "Experiments using arms"):
// an N-link arm (2 or 3 in the paper) turning about z on a table, torque motors on every joint,
// reaching for a target that moves. The paper: "4s episodes during which the target position
// changes every second", reward "proportional to squared distance between the end-effector and
// the target center minus a small control cost". Here the target is re-drawn uniformly (by area)
// in an annulus every `target_period` seconds; the 3-link default has the same total reach as the
// 2-link one, so both arms can reach every target (the annulus is checked at construction).
//
// Physics follow OpenAI Gym's Reacher (the public relative of these arms): 10 ms RK4 steps, 2
// per action (50 Hz control), joint armature 1 and damping 1, gear 200, ctrlrange -1..1. Joints
// are unlimited and links do not collide, so the reachable set is exactly the annulus
// [max(0, 2 max(l) - sum(l)), sum(l)].
//
// Observations (by name):
//   full          cos q, sin q, q', target xy, fingertip xy, target - fingertip
//                 (seed 000's policy input; its ee_to_target slice is what the cross-body
//                 discriminator sees)
//   ee_to_target  target - fingertip only (2 values)
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "env/mjcf_env.hpp"

namespace mimic {

struct ReacherConfig {
  std::vector<double> link_lengths{0.1, 0.11};  // base to fingertip (Gym Reacher's 2-link arm)
  std::string observation = "full";
  double timestep = 0.01;
  int frame_skip = 2;
  int max_steps = 200;                 // 4 s at 50 Hz (seed 000)
  double target_period = 1.0;          // seconds between target draws; <= 0: a fixed target
  double target_min_radius = 0.05;     // target annulus around the base (m)
  double target_max_radius = 0.20;
  bool squared_distance = false;       // reach = -d (Gym) or -d^2 (seed 000's wording)
  double control_weight = 1.0;         // control = -weight * |u|^2 (Gym Reacher)
  double reset_angle_noise = 0.1;      // uniform initial joint angles (rad) and rates (rad/s)
  double reset_velocity_noise = 0.005;

  static ReacherConfig two_link() { return {}; }
  static ReacherConfig three_link() {
    ReacherConfig c;
    c.link_lengths = {0.07, 0.07, 0.07};  // total reach 0.21 m, as the 2-link default
    return c;
  }
};

// Inner and outer radius the fingertip can reach (unlimited joints).
std::pair<double, double> reach_annulus(const std::vector<double>& link_lengths);
std::string reacher_arm_mjcf(const ReacherConfig& cfg);

class ReacherArmEnv : public MjcfEnv {
 public:
  explicit ReacherArmEnv(const ReacherConfig& cfg = {});

  int observation_size() const override { return obs_size_; }
  std::vector<ObservationSlice> observation_layout() const override;
  Eigen::VectorXd reset(std::mt19937_64& rng) override;
  // Terms "reach" (distance during this step's target) and "control". The target is re-drawn
  // after the step that completes a period, so the returned observation shows the new one.
  StepResult step(const Eigen::VectorXd& action) override;
  int view_camera() const override { return 0; }  // "top": the arm moves in the table's plane, seen from above

  const ReacherConfig& config() const { return cfg_; }
  int links() const { return static_cast<int>(cfg_.link_lengths.size()); }
  int target_period_steps() const { return period_steps_; }
  Eigen::VectorXd observation() const;
  Eigen::Vector2d fingertip() const;
  const Eigen::Vector2d& target() const { return target_; }
  // Moves the target (tests, scripted demonstrations); it stays until the next draw.
  void set_target(const Eigen::Vector2d& target);
  int steps() const { return steps_; }

 private:
  void draw_target();

  ReacherConfig cfg_;
  int obs_size_ = 0;
  int period_steps_ = 0;
  int fingertip_site_ = -1;
  int target_mocap_ = -1;
  int steps_ = 0;
  bool started_ = false;
  Eigen::Vector2d target_ = Eigen::Vector2d::Zero();
  std::mt19937_64 target_rng_;  // seeded from reset()'s rng: step() draws targets without one
};

}  // namespace mimic
