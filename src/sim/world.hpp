#pragma once
// A simulated character in MuJoCo: owns mjModel/mjData, steps physics at physics_hz under PD
// servos updated at control_hz, and moves between mimic poses and MuJoCo state.
#include <memory>
#include <string>
#include <vector>

#include "motion/kinematics.hpp"
#include "sim/character_model.hpp"

struct mjModel_;
struct mjData_;

namespace mimic {

// What a joint's torque limit bounds. `Spring`: the spring part alone, the damping (MuJoCo's joint
// damping) unbounded, so a joint driven at its limit stops speeding up at limit / kd rad/s (2-4 rad/s
// for DeepMimic's humanoid). `Total`: spring and damping together, as DeepMimic's PD controllers,
// so a joint swings as fast as its torque can accelerate it (its run asks 10-18 rad/s).
enum class PdLimit { Spring, Total };

struct SimConfig {
  double physics_hz = 600.0;
  double control_hz = 30.0;
  PdLimit pd_limit = PdLimit::Spring;
};

// A character's whole-body momentum in one state, in the world frame: mass, centre of mass, its
// velocity, the angular momentum about it and the inertia tensor about it (SI units).
struct BodyMomentum {
  double mass = 0.0;
  Vec3 com = Vec3::Zero(), com_velocity = Vec3::Zero(), angular = Vec3::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
};

class World {
 public:
  // Builds the MJCF of `ch` and compiles it; throws Error with MuJoCo's message on failure.
  World(const CharacterModel& ch, const SimConfig& cfg = {});
  // The same with model options (terrain, extra bodies); the timestep comes from `cfg`.
  World(const CharacterModel& ch, const SimConfig& cfg, MjcfOptions model);
  // Compiles a given MJCF text for `ch`'s skeleton (joint names must match).
  World(const CharacterModel& ch, const std::string& mjcf, const SimConfig& cfg);
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  const CharacterModel& character() const { return ch_; }
  const SimConfig& config() const { return cfg_; }
  int substeps() const { return substeps_; }
  double time() const;

  // Sets the character's full state: a pose and its velocities (zero when omitted).
  void set_state(const Pose& pose, const PoseVelocity* vel = nullptr);
  // The current pose (root position and rotation, joint rotations).
  Pose pose() const;
  // The root's position alone (cheaper than pose() for per-step checks).
  Vec3 root_position() const;
  // Writes `pose` into `other`, data of this world's model (a ghost to draw), and places its
  // bodies (mj_kinematics); this world's own state is untouched.
  void write_pose(const Pose& pose, mjData_* other) const;
  // The character's momentum in the state (pose, vel), worked out on scratch data: this world's
  // own state is untouched, but the scratch is shared, so one thread at a time, as for stepping.
  // Throws as set_state.
  BodyMomentum momentum_of(const Pose& pose, const PoseVelocity& vel) const;
  // The current velocities, as set_state takes them (root in the world frame, joints in their own).
  PoseVelocity velocity() const;
  // PD targets: one rotation per joint (root ignored). Torques are clamped to torque limits
  // (SimConfig::pd_limit says which part).
  void set_pd_targets(const Pose& targets);
  // Advances one control step (physics_hz / control_hz physics steps).
  void step();
  // The same with no joint torques: a limp body under gravity and its joints' damping (a ragdoll
  // settling where it fell).
  void step_limp();

  // World frames of every joint (= MuJoCo body frames) and the skeleton's sites.
  LinkFrames link_frames() const;
  Vec3 centre_of_mass() const;
  // Per joint: does its body touch the floor (or another non-character geom)?
  std::vector<bool> ground_contacts() const;
  // Per joint: does its body come within `gap` metres of the floor (or another world-fixed geom)
  // in `pose`? Read on scratch data: the world's state is untouched.
  std::vector<bool> ground_contacts_of(const Pose& pose, double gap) const;
  // How far the character's bodies reach into the floor (or another world-fixed geom) in the
  // current state, metres; 0 when none does. Read from the contacts of the last mj_forward.
  double ground_penetration() const;

  mjModel_* model() const { return m_; }
  mjData_* data() const { return d_; }

 private:
  void init(const std::string& mjcf);
  void apply_pd();
  // Per joint: does its body touch a world-fixed geom in `d`'s contacts?
  std::vector<bool> contacts_with_world(const mjData_* d) const;
  void set_targets(const std::vector<Quat>& rot);

  CharacterModel ch_;
  SimConfig cfg_;
  int substeps_ = 1;
  mjModel_* m_ = nullptr;
  mjData_* d_ = nullptr;
  mutable mjData_* scratch_ = nullptr;  // momentum_of's, made on first use
  std::vector<int> body_, qpos_, dof_;  // per skeleton joint; -1 for none
  std::vector<Quat> target_;
  std::vector<double> target_angle_;  // revolute joints' target angles (from target_)
};

}  // namespace mimic
