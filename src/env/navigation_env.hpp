#pragma once
// Seed 000's high-level controller task (Merel et al. 2017 §5 and supplement): a frozen
// low-level skill walks the character, and the high-level controller (HLC), trained by RL,
// chooses what the skill does every `decision_steps` control steps from what lies ahead. Here the
// low-level skill is a steered one (trained with `goal: heading`, seed 004 eq. 8) and the HLC's
// choice is its heading: an action a in [-1, 1] commands the world yaw a * max_turn (degrees
// from the course's +x). The HLC observes, as seed 000's:
//   height_map  the ground's height above the ground under the root on a grid in the heading
//               frame, from 0 to view_ahead metres ahead and view_width wide (seed 000: 15 m
//               ahead, 8 m, "seeing roughly two walls ahead"); a wall reads as its height
//   heading     cos and sin of the character's facing against the course's +x
//   lateral     the root's y over the course's half width (no position along the course)
// (with height_map false, only the last two: seed 000's HLC without its view), and is rewarded
// progress_weight per metre along +x. A fall of the skill's environment ends the episode (a
// failure), and so does leaving the course sideways (the root beyond its half width: seed 000's
// track is a corridor, and around its walls is no way through); its time limit or max_seconds
// end it too (not failures).
#include <deque>
#include <functional>
#include <memory>

#include "env/character_env.hpp"

namespace mimic {

struct NavigationConfig {
  int decision_steps = 10;   // control steps per decision (1/3 s at 30 Hz)
  double max_turn = 60.0;    // degrees: the command of an action of +-1
  double view_ahead = 15.0, view_width = 8.0, view_spacing = 0.5;  // metres
  double progress_weight = 1.0;
  double max_seconds = 30.0;
  bool height_map = true;    // false: the controller sees no terrain, only its heading and lateral place (seed 000's comparison)
};

// The controller's observation (the layout above) for a character whose root is at `root` facing
// world yaw `yaw`, the ground's height at (x, y) given by `ground` and the course `half_width`
// wide either side of its axis: what NavigationEnv observes, and what a runtime session driving a
// skill by a trained controller computes from its own world (control/navigation.hpp).
struct NavigationView {
  explicit NavigationView(const NavigationConfig& cfg);
  int ahead = 0, across = 0;  // grid points along and across the view
  int size() const { return (cfg.height_map ? ahead * across : 0) + 3; }
  Eigen::Vector2d point(const Vec3& root, double yaw, int i, int j) const;  // world (x, y) of cell (i along, j across)
  Eigen::VectorXd observe(const Vec3& root, double yaw, const std::function<double(double, double)>& ground, double half_width) const;
  // The world yaw (radians) an action commands: a in [-1, 1] (clipped; not finite: 0) times max_turn.
  double command(double action) const;
  NavigationConfig cfg;
};

// The low-level skill's policy: its stacked observation frames (oldest first) to its action.
using LowLevelPolicy = std::function<Eigen::VectorXd(const Eigen::VectorXd&)>;

class NavigationEnv final : public Env {
 public:
  // `skill_env` must have a heading goal (env.goal: heading) and its own redraws off (a
  // goal_period longer than an episode); `history` is how many frames `policy` takes. Throws Error
  // otherwise, or for a config out of range.
  NavigationEnv(std::unique_ptr<CharacterEnv> skill_env, LowLevelPolicy policy, int history, const NavigationConfig& cfg);

  int observation_size() const override { return view_.size(); }
  int action_size() const override { return 1; }
  std::vector<ObservationSlice> observation_layout() const override;
  Eigen::VectorXd reset(std::mt19937_64& rng) override;
  StepResult step(const Eigen::VectorXd& action) override;
  const mjModel_* physics_model() const override { return inner_->physics_model(); }
  mjData_* physics_data() const override { return inner_->physics_data(); }
  double control_dt() const override { return cfg_.decision_steps * inner_->control_dt(); }  // one decision
  int view_camera() const override { return inner_->view_camera(); }

  CharacterEnv& character() { return *inner_; }
  const NavigationConfig& config() const { return cfg_; }
  // The commanded world yaw of an action (radians).
  double command_of(double action) const;
  // World (x, y) of height-map cell (i along, j across) for a character at `root` facing `yaw`.
  Eigen::Vector2d view_point(const Vec3& root, double yaw, int i, int j) const;

 private:
  Eigen::VectorXd observe() const;
  Eigen::VectorXd stacked() const;
  void command(double yaw);

  std::unique_ptr<CharacterEnv> inner_;
  LowLevelPolicy policy_;
  int history_;
  NavigationConfig cfg_;
  NavigationView view_;
  int goal_offset_ = -1;  // the "goal" part of the skill's observation
  std::deque<Eigen::VectorXd> frames_;
  double elapsed_ = 0.0;
};

}  // namespace mimic
