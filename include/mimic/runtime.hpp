#pragma once
// mimic's runtime: load a trained skill and step a simulated character with it, without LibTorch.
// The whole public surface for a game, a robot stack or a tool (docs/runtime.md). Depends on the
// C++20 standard library and Eigen only; links MuJoCo (find_package(mimic) gives mimic::runtime).
//
//   auto walk = mimic::Skill::load("models/humanoid_walk_iccgan");
//   mimic::Controller controller({walk});
//   for (int i = 0; i < 300; ++i) controller.step();      // 10 s at 30 Hz
//   Eigen::Vector3d root = controller.root_position();
//
// Model vs state, as MuJoCo's mjModel and mjData: a Skill is constant once loaded and may be
// shared by any number of controllers and threads; a Controller is the changing state of one
// character and belongs to one thread at a time.
#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

struct mjModel_;
struct mjData_;

namespace mimic {

// A trained skill: its networks (networks.mimic, written by `mimic export`) and the environment it
// was trained in (config.yaml's `env`: the character, its observations and its action mapping).
class Skill {
 public:
  // A model directory (mimic export). `name` defaults to default_name(model_dir). `env_settings`
  // change the skill's environment as `mimic eval --set` does ("env.max_seconds=30"; env keys
  // only). Throws std::runtime_error (mimic::Error) naming the file and the problem: a missing
  // file, a damaged or truncated one (CRC-32), a newer format, a layer of the wrong shape, a
  // weight that is not finite, networks whose sizes or character differ from the config's
  // environment, a setting that does not fit it.
  static std::shared_ptr<const Skill> load(const std::filesystem::path& model_dir, const std::string& name = "",
                                           const std::vector<std::string>& env_settings = {});
  // The name of a model loaded without one: its directory's, or for a directory named `model`
  // (the one `mimic imitate` writes in its run: runs/my_walk/model) the run's (my_walk).
  static std::string default_name(const std::filesystem::path& model_dir);
  struct Impl;
  explicit Skill(std::unique_ptr<Impl> impl);  // what load() builds
  ~Skill();
  Skill(const Skill&) = delete;
  Skill& operator=(const Skill&) = delete;

  const std::string& name() const;
  const std::filesystem::path& directory() const;
  int frame_size() const;   // one observation
  int history() const;      // frames the policy sees, oldest first
  int input_size() const;   // frame_size() * history()
  int action_size() const;
  long long policy_parameters() const;
  // The policy's mean actions for raw policy inputs (rows; the observation normaliser is applied
  // here), and the value network's estimates.
  Eigen::MatrixXd act(const Eigen::MatrixXd& inputs) const;
  Eigen::VectorXd act(const Eigen::VectorXd& input) const;
  Eigen::VectorXd value(const Eigen::MatrixXd& inputs) const;
  // The same in float32 row-major, without conversions (benchmarks, batched games). `inputs`
  // is [batch, input_size()] row-major; returns [batch, action_size()] row-major.
  std::vector<float> act_floats(const float* inputs, int batch) const;
  // The discriminators the skill learnt against (its adversarial reward sources: seed 000's GAIL,
  // seed 004's ensemble), by source name; empty for a skill trained on another reward.
  std::vector<std::string> discriminators() const;
  // How expert-like discriminator `source` finds transitions: its reward for each row of
  // (observation frame without a behaviour context, the next frame, the action), under behaviour
  // context `context` (-1 for a skill without contexts). Seed 004 switches skills by these
  // scores. Throws mimic::Error for an unknown source, a missing context or rows that do not fit.
  Eigen::VectorXd score(const std::string& source, const Eigen::MatrixXd& obs, const Eigen::MatrixXd& next_obs, const Eigen::MatrixXd& actions,
                        int context = -1) const;

  const Impl& impl() const { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

// What a control step did.
struct StepInfo {
  bool episode_over = false;  // the skill's environment ended the episode (below: why)
  bool fell = false;          // a fall or a drift from the reference: a failure
  std::string ending;         // "fall", "time limit", "clip end", "drift"; empty while it goes on
  bool ground_contact = false;  // a body whose ground contact the skill counts as a fall touches the ground now
  std::string switched_to;    // a requested skill took over after this step (it acts from the next)
  std::string dropped;        // a request that no step allowed within the rule's time limit
  double target_score = std::nan("");  // the pending request's figure at this step, as the rule measures it
};

// When a requested skill takes over (seed 004 section 5.3). By its score: the mean over its
// discriminator ensemble's heads of clip(D_i, -1, 1) for the character's current trajectory (the
// frames its discriminator sees) reaches `threshold` (eq. 6's tau). By its value: its value
// network's estimate of the current state reaches `threshold` (the paper's baseline). By pose
// matching: 1 - (mean joint distance from the character's pose to the nearest frame of the
// skill's clips, poses in their heading frames) / (the clips' own spread about their mean pose)
// reaches `threshold` (motion matching's baseline: 1 at a frame of the clip). Or at once.
struct SwitchRule {
  enum class By { Score, Value, Matching, Immediately };
  By by = By::Score;
  double threshold = 0.2;
  // After a skill takes over, requests wait this many control steps (seed 004: 20 frames after a
  // jump, so that it is done before another policy is asked).
  int delay_steps = 0;
  // A request that no step allows within this is dropped, and the step says so.
  double time_limit_seconds = 2.0;
};

// One character in one MuJoCo world, driven by one of a set of skills of that character.
class Controller {
 public:
  // Skills of one character (the same MuJoCo bodies, the same action size); the first is active.
  // `seed` draws the environments' starts. Throws mimic::Error naming the skill that differs.
  explicit Controller(std::vector<std::shared_ptr<const Skill>> skills, std::uint64_t seed = 1);
  ~Controller();
  Controller(const Controller&) = delete;
  Controller& operator=(const Controller&) = delete;

  // A new episode of the active skill, from its environment's start distribution.
  void reset();
  // A new episode of `skill` (made active) from a state of the character given in MuJoCo's terms:
  // `qpos` and `qvel` (physics_model()'s nq and nv numbers), and `past`, the qpos of the control
  // steps before it, oldest first, that fill the history the skill observes (empty: the state
  // repeated). `clip_time`: where on the skill's reference clip the state is, for a skill that
  // tracks one. A game hands its own animation's character to a skill this way; `mimic complete`
  // starts a skill from a pose seen in a still (seed 003 §8). Throws mimic::Error naming the skill
  // for a skill that drives no character, vectors of other sizes or numbers that are not finite.
  void start(const std::string& skill, const Eigen::VectorXd& qpos, const Eigen::VectorXd& qvel,
             const std::vector<Eigen::VectorXd>& past = {}, double clip_time = 0.0);
  // One control step: the active skill's policy mean, applied through its PD targets.
  StepInfo step();
  // Hands the character, in its current state (pose, velocities and its last poses), to another
  // skill now. Throws mimic::Error naming the skills it knows when `skill` is not one of them.
  void switch_to(const std::string& skill);
  // Asks for `skill`: it takes over after the first step whose state the switch rule allows, or
  // the request is dropped after the rule's time limit (StepInfo says which). A new request
  // replaces a pending one; asking for the active skill cancels it.
  void request(const std::string& skill);
  const std::string& requested() const;  // the pending request; empty when none
  void set_switch_rule(const SwitchRule& rule);
  const SwitchRule& switch_rule() const;
  // The skill's switch score of the character's current state, in [-1, 1] (seed 004 eq. 6), and
  // its value network's estimate; what the rule compares with its threshold. The score throws for
  // a skill without discriminators (Skill::discriminators()).
  double score(const std::string& skill);
  double value(const std::string& skill);
  // The skill's pose-matching readiness of the character's current pose (SwitchRule::By::Matching's
  // figure); throws for a skill whose starts come from no clip.
  double matching(const std::string& skill);

  // Pushes the character: `force` (world frame, newtons) on its root link through the next
  // `seconds` (a hand-over carries the rest over). A new push replaces one under way. Throws
  // mimic::Error for a force that is not finite, seconds < 0 or a skill that is not a character.
  void push(const Eigen::Vector3d& force, double seconds);
  // Throws a cube (seed 004's projectiles) at a random point of the character's torso from a
  // random direction, in the active skill's world; false where that world has no cubes. Skills get
  // them by Skill::load's env settings: "env.projectiles.enabled=true" and, for cubes only when
  // thrown, "env.projectiles.every=0" (mass, size and speed are settings too). A cube stays in the
  // world of the skill that threw it: a hand-over leaves it behind.
  bool throw_cube();
  // Steering, for skills trained with a heading goal (`mimic imitate --task heading`, seed 004
  // eq. 8): the direction they walk towards from the next step on, as a world yaw (radians about
  // z from +x), held until changed. Before a command they follow the targets their environment
  // draws; skills without the goal ignore it. Throws mimic::Error for a yaw that is not finite.
  void set_heading(double yaw);
  double heading() const;                          // the commanded yaw; NaN before a command
  bool steerable(const std::string& skill) const;  // trained with a heading goal; throws for an unknown skill
  double facing() const;                           // where the character faces now (its root's world yaw)
  // The top of the ground at world (x, y) in the active skill's world (its terrain: a step, a
  // wall's top, a gap's floor; 0 on flat ground), and half the width of its course (NaN for a
  // skill that drives no character).
  double ground_height(double x, double y) const;
  double course_half_width() const;

  const std::string& skill() const;  // the active one's name
  const std::vector<std::shared_ptr<const Skill>>& skills() const;
  double control_dt() const;         // seconds per step()
  double time() const;               // seconds since reset()
  long long steps() const;           // since reset()
  Eigen::Vector3d root_position() const;  // world frame, metres, z up
  // The highest of the character's joints above the ground under its root, metres (the head's
  // when it stands; lower bent over or kneeling); 0 for a skill that drives no character.
  double highest_joint_height() const;
  // Which side the character lies on: +1 face up, -1 face down (its root's forward axis more than
  // 30 degrees above or below the horizontal), 0 neither (standing, on its side, or a skill that
  // drives no character). Recovery hands a fallen character to the get-up of its side.
  int lying_side() const;
  // The last policy input and action (raw, before normalisation / PD mapping).
  const Eigen::VectorXd& last_input() const;
  const Eigen::VectorXd& last_action() const;
  // The MuJoCo model and state of the active skill's world, for a renderer (read only between steps).
  const mjModel_* physics_model() const;
  mjData_* physics_data() const;

  struct Impl;

 private:
  friend struct ControllerInternals;  // the control layer's own reads (src/control/controller_internals.hpp)
  std::unique_ptr<Impl> impl_;
};

}  // namespace mimic
