#pragma once
// A simulated character as an environment: actions are PD targets, observations are built by
// name (observations.hpp), episodes end on falls (chosen bodies touching the ground), at a time
// limit, or at the end of a non-cyclic reference clip. Tasks add reward terms. The ground is a
// Terrain (sim/terrain.hpp); pushes and projectiles (sim/perturbation.hpp) perturb the character.
#include <functional>
#include <limits>
#include <memory>
#include <optional>

#include "env/observations.hpp"
#include "sim/perturbation.hpp"
#include "sim/terrain.hpp"

namespace mimic {

enum class ActionMode {
  AxisAngle,   // 3 per spherical joint (rotation vector), 1 per revolute (angle); clipped to +-pi
  Quaternion,  // 4 per spherical joint (normalised; zero = identity), 1 per revolute
};

// How a start drawn from a clip gets the clip's momentum over a window instead of the instant's
// (smooth_start_momentum).
struct StartMomentumSmoothing {
  enum class Statistic {
    Mean,    // the mean of the window's states
    Median,  // per component: a spike shorter than half the window leaves it alone, and the
             // clip's steady changes within a stride pass through
  };
  double window = 0.0;  // seconds each side of the start; 0: off
  Statistic statistic = Statistic::Mean;
  bool linear = true;  // also the horizontal linear momentum; false: the angular momentum only
};

inline constexpr const char* kAllFallLinks = "all";  // CharacterEnvConfig::fall_links: every body

struct CharacterEnvConfig {
  SimConfig sim;
  ObservationConfig observations;
  ActionMode action_mode = ActionMode::AxisAngle;
  // Bodies whose ground contact ends the episode as a fall. Empty: the character's own choice
  // (DeepMimic's EnableFallContact); the one name "all" (kAllFallLinks): every body, for any
  // character, with allow_clip_contacts sparing those the clip rests on (a walk's feet: DeepMimic's
  // rule, any contact but the feet's). early_termination = false turns falls off (contact-rich clips).
  std::vector<std::string> fall_links;
  // Bodies that the clips themselves rest on the ground (CharacterEnv::allow_contacts_of: a
  // get-up's hands, elbows and back) touch it without a fall; the rest of fall_links stay falls. A
  // rule from the clip, so one recipe holds for a walk and a get-up alike.
  bool allow_clip_contacts = false;
  bool early_termination = true;
  // > 0: also a fall when the root is below this fraction of the reference's root height at the
  // current clip time, e.g. sitting on the thighs with the torso off the ground, which no torso
  // contact catches and which a tracking policy otherwise learns to settle into. Needs a reference.
  double fall_height = 0.0;
  // > 0: the episode ends as Drift (a failure) once the root is more than this many metres from
  // the reference's, horizontally: a tracking policy that falls behind a fast clip loses the rest
  // of the episode instead of trotting on in place (MimicKit's pose termination). Needs a reference,
  // or starts that name the clip they were drawn from (InitState::source).
  double max_drift = 0.0;
  double max_seconds = 20.0;  // TimeLimit
  // Raise every start, with its past poses, out of the floor: by the depth its bodies reach into
  // it, plus 1 mm. Mocap poses put a foot inside the floor at some phases (the run clip: 1.9 cm at
  // its first frame, 4.9 cm at 0.45 of its cycle), and the contact's push then throws the character
  // off its stride. DeepMimic does the same (ResolveCharGroundIntersect). Off by default: the
  // committed models were trained without it.
  bool lift_starts = false;
  // window > 0: a start drawn from a clip (state_on_clip) carries the clip's whole-body momentum
  // over t +- window, not the instant's (smooth_start_momentum). Off by default: most committed
  // models were trained without it.
  StartMomentumSmoothing start_momentum;
  TerrainSpec terrain;             // flat by default; every kind starts flat around the origin
  std::vector<PushSpec> pushes;    // times from each episode's start
  ProjectileSpec projectiles;      // seed 004's projectile test when enabled
};

// The clip a start was drawn from when it is not the env's reference, the time on it, and the
// rigid move that placed the start (place_at_track_start): max_drift measures the root against
// that clip's root played on from there, moved the same way.
struct StartSource {
  std::shared_ptr<const Clip> clip;
  double time = 0.0;
  Quat turn = Quat::Identity();  // about the vertical, then
  Vec3 offset = Vec3::Zero();    // a shift
  Vec3 place(const Vec3& p) const { return turn * p + offset; }
};

// Where an episode starts: a pose, its velocities, and the time on the reference clip. `past`:
// poses one control step apart before `pose`, oldest first, that seed the "links" history (seed
// 004: the discriminator sees frames t-3...t+1 from the first step on); empty: the start repeats.
// `clip_left`: seconds after which the episode ends as ClipEnd, for starts drawn from a non-cyclic
// clip that is not the env's reference (seed 004 ends a kick where its clip ends). `source`: where
// such a start came from; empty: drift is measured against the reference, if any. `lying`: a start
// on the ground already (a get-up's fallen start): contacts that would end an episode as a fall do
// not end this one, its time limits still do.
struct InitState {
  Pose pose;
  PoseVelocity velocity;
  double time = 0.0;
  std::vector<Pose> past;
  double clip_left = std::numeric_limits<double>::infinity();
  StartSource source = {};
  bool lying = false;
};
// The clip's state at `t`, with the `past` poses at t - past * dt, ..., t - dt (before the clip's
// start a wrapping clip wraps, others hold their first frame).
InitState init_state_from_clip(const Clip& clip, double t, int past = 0, double dt = 0.0);
// Gives a start `s` (the clip's state at `t`) the clip's whole-body momentum over t +- window (the
// mean or per-component median of 17 evenly spaced states): the angular momentum about the centre
// of mass by a rigid spin of the whole body about it, the horizontal linear momentum (when
// `smoothing.linear`) by a shift of every link's velocity; joint velocities and the com's vertical
// velocity stay. Why: velocities from frame differences are not a physical state at every phase.
// At the run clip's touchdown at half its cycle the angular momentum is over 8 kg m^2/s and the com
// moves sideways at over 0.4 m/s for two frames (over +-0.1 s: a mean under 2.5 and 0.2, a median
// of |L| under 1); a simulated start keeps the instant's, and it throws the character off the
// clip's line. `world` is the character's (read on scratch data). Throws Error unless window > 0.
void smooth_start_momentum(const World& world, const Clip& clip, double t, const StartMomentumSmoothing& smoothing,
                           InitState& s);

class CharacterEnv : public Env {
 public:
  using RewardTerm = std::function<double(const CharacterEnv&)>;
  using InitSampler = std::function<InitState(std::mt19937_64&)>;

  CharacterEnv(const CharacterModel& ch, const CharacterEnvConfig& cfg, std::shared_ptr<const Clip> reference = nullptr);

  int observation_size() const override { return obs_.size() + extra_size_; }
  int action_size() const override { return action_size_; }
  std::vector<ObservationSlice> observation_layout() const override;
  // Starts from the init sampler's state: by default the reference clip's start, or standing.
  Eigen::VectorXd reset(std::mt19937_64& rng) override;
  Eigen::VectorXd reset(const InitState& init);
  // The clip's state at `t` with as many past poses as the observation's history uses, its
  // momentum smoothed when config().start_momentum.window > 0.
  InitState state_on_clip(const Clip& clip, double t) const;
  StepResult step(const Eigen::VectorXd& action) override;
  const mjModel_* physics_model() const override { return world_.model(); }
  mjData_* physics_data() const override { return world_.data(); }
  double control_dt() const override { return 1.0 / world_.config().control_hz; }

  void set_init_sampler(InitSampler sampler) { init_sampler_ = std::move(sampler); }
  // Starts in groups a caller can choose among (imitation: one group per clip of its list),
  // so a behaviour context can start each episode from its own clip. The sampler reads the choice.
  int start_groups() const { return start_groups_; }
  void set_start_groups(int n) { start_groups_ = n; }
  int start_group() const { return start_group_; }  // -1: starts from every group
  void choose_start_group(int g);                   // Error outside [-1, start_groups())
  void add_reward_term(std::string name, RewardTerm term) { rewards_.emplace_back(std::move(name), std::move(term)); }
  // A task's own observation part (a goal, say), appended after the named ones: `fill` writes
  // `size` values. Add parts before the first reset.
  using ObservationPart = std::function<void(const CharacterEnv&, Eigen::Ref<Eigen::VectorXd>)>;
  void add_observation_part(std::string name, int size, ObservationPart fill);
  // The most one step can earn, for normalised returns; 0 when the task does not bound it.
  double max_step_reward() const { return max_step_reward_; }
  void set_max_step_reward(double r) { max_step_reward_ = r; }
  // Removes from the fall bodies those `clip` puts on the ground (allow_clip_contacts); the env
  // does this for its reference, the imitation env for its clips.
  void allow_contacts_of(const Clip& clip);
  // A body rests on the ground at a frame of a clip when it is within kClipContactGap of it (mocap
  // bodies hover a little: the face-up get-up's pelvis lies 4.5 cm up) with its joint below
  // kClipContactJointHeight of the standing root height (a run's shin comes as near beside its
  // planted foot, the knee high); in the clip, when it does so for kClipContactSeconds in all.
  static constexpr double kClipContactGap = 0.05;          // m
  static constexpr double kClipContactJointHeight = 0.25;  // of rest_root_height()
  static constexpr double kClipContactSeconds = 0.1;
  // The bodies whose ground contact is a fall, by joint name.
  std::vector<std::string> fall_bodies() const;
  // Replaces the pushes (e.g. new random pushes per episode); throws Error on an unknown link.
  void set_pushes(std::vector<PushSpec> pushes);

  // PD targets an action stands for.
  Pose targets_from_action(const Eigen::VectorXd& action) const;
  // The action that sets these PD targets (its inverse, for scripted playback and tests).
  Eigen::VectorXd action_for(const Pose& targets) const;
  const World& world() const { return world_; }
  World& world() { return world_; }
  const Clip* reference() const { return reference_.get(); }
  const std::shared_ptr<const Clip>& shared_reference() const { return reference_; }
  double time() const { return time_; }  // on the reference clip: init time + elapsed
  double elapsed() const { return elapsed_; }
  long long starts() const { return starts_; }  // episodes begun (reset(InitState) calls), for tasks that mark one
  bool lying_start() const { return lying_; }   // the episode under way began lying (InitState::lying)
  const CharacterEnvConfig& config() const { return cfg_; }
  const Terrain& terrain() const { return terrain_; }
  // The terrain's curriculum (config().terrain.levels > 0; seed 002 section 3.1.2, each environment
  // keeping its own level as legged_gym's terrain curriculum does): the env starts at level 1, and
  // at each start after an episode it goes a level up where that episode's root got
  // kCurriculumMargin past the course's end (crossed it), a level down where it ended in a failure
  // before the middle of the course, and stays otherwise. Steps report the level as the info
  // "terrain_level".
  static constexpr double kCurriculumMargin = 0.5;  // m, as the crossing trials'
  int terrain_level() const { return terrain_.level(); }
  // Does a body whose contact counts as a fall touch the ground now (whether or not that ends
  // episodes)? The robustness test counts frames lying on the ground.
  bool fall_contact() const;
  // The root below fall_height times the reference's root height (false without either).
  bool below_reference() const;
  // The root's horizontal distance from the reference's at the current clip time, or else from the
  // start's source clip played on from the start (0 without either).
  double drift() const;
  const StartSource& start_source() const { return source_; }  // the episode's start's
  // The pose the character is measured against now, as drift() measures the root: the reference's
  // at the clip time, or else the start's source clip played on from the start and placed as the
  // start was. None without either (what `mimic render --ghost` draws).
  std::optional<Pose> reference_pose() const;
  // The projectile launcher (null unless config().projectiles.enabled); its stats are per episode.
  const ProjectileLauncher* projectiles() const { return launcher_.get(); }
  ProjectileLauncher* projectiles() { return launcher_.get(); }

 protected:
  // Called by reset(InitState) once the start is placed, before its first observation: a task's
  // own state for the new episode (a goal drawn from where the character faces, say).
  virtual void on_start() {}

 private:
  Eigen::VectorXd observe();
  Termination check_termination() const;
  void update_terrain_level();  // at a start: the curriculum's rule on the episode before
  // How far to raise a start out of the floor (CharacterEnvConfig::lift_starts); 0 when off.
  double start_lift(const Pose& pose);
  static constexpr double kStartLiftPad = 1e-3;  // m above the deepest point, as DeepMimic's pad

  CharacterEnvConfig cfg_;
  Terrain terrain_;
  World world_;
  std::shared_ptr<const Clip> reference_;
  ObservationBuilder obs_;
  int action_size_ = 0;
  std::vector<int> fall_joints_;
  std::deque<LinkFrames> history_;
  std::vector<std::pair<std::string, RewardTerm>> rewards_;
  struct ExtraPart {
    std::string name;
    int size;
    ObservationPart fill;
  };
  std::vector<ExtraPart> extra_;
  int extra_size_ = 0;
  InitSampler init_sampler_;
  long long starts_ = 0;
  double farthest_x_ = 0.0;           // the episode's farthest root x (the curriculum's rule)
  bool episode_failed_ = false;       // the episode ended in a failure
  int start_groups_ = 0, start_group_ = -1;
  Pusher pusher_;
  std::unique_ptr<ProjectileLauncher> launcher_;
  double time_ = 0.0, elapsed_ = 0.0;
  double clip_left_ = std::numeric_limits<double>::infinity();  // the start's InitState::clip_left
  bool lying_ = false;                                           // and InitState::lying
  StartSource source_;                                           // and its source
  double max_step_reward_ = 0.0;
};

}  // namespace mimic
