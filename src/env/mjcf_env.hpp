#pragma once
// A base for torque-controlled environments defined directly by an MJCF text (not by a mimic
// character): owns the compiled mjModel/mjData, applies actions as actuator controls clipped to
// each actuator's ctrlrange, advances `frame_skip` physics steps per control step and reads the
// state back. Subclasses add observations, rewards and terminations.
#include <Eigen/Core>
#include <string>

#include "env/env.hpp"

struct mjModel_;
struct mjData_;

namespace mimic {

class MjcfEnv : public Env {
 public:
  // Compiles `mjcf` (errors: mimic::Error naming `name` with MuJoCo's message).
  // `timestep` > 0 overrides the MJCF's option/timestep; frame_skip >= 1.
  MjcfEnv(std::string name, const std::string& mjcf, int frame_skip, double timestep = 0.0);
  ~MjcfEnv() override;
  MjcfEnv(const MjcfEnv&) = delete;
  MjcfEnv& operator=(const MjcfEnv&) = delete;

  int action_size() const override;
  const mjModel_* physics_model() const override { return m_; }
  mjData_* physics_data() const override { return d_; }

  const std::string& name() const { return name_; }
  const mjModel_* model() const { return m_; }
  const mjData_* data() const { return d_; }
  int frame_skip() const { return frame_skip_; }
  double physics_dt() const;
  double control_dt() const override { return physics_dt() * frame_skip_; }
  double time() const;

  // Generalised state. set_state checks sizes and recomputes positions (mj_forward).
  Eigen::VectorXd qpos() const;
  Eigen::VectorXd qvel() const;
  void set_state(const Eigen::VectorXd& qpos, const Eigen::VectorXd& qvel);

  // Ids by name (Error when absent) and world positions, valid after reset/step/set_state.
  int body_id(const std::string& body) const;
  int site_id(const std::string& site) const;
  Eigen::Vector3d body_pos(int body) const;
  Eigen::Vector3d site_pos(int site) const;

  // The action clipped to the actuators' ctrlrange. Error on a wrong size or a non-finite entry
  // (a learner bug, not an out-of-range action).
  Eigen::VectorXd clip_action(const Eigen::VectorXd& action) const;

 protected:
  // Back to the model's initial state (qpos0, zero velocity, time 0), positions computed.
  void reset_data();
  // Sets the clipped action as controls, runs frame_skip physics steps and recomputes positions
  // so that body/site positions match the new qpos. Returns the clipped action.
  Eigen::VectorXd simulate(const Eigen::VectorXd& action);
  mjData_* mutable_data() { return d_; }

 private:
  std::string name_;
  int frame_skip_ = 1;
  mjModel_* m_ = nullptr;
  mjData_* d_ = nullptr;
};

}  // namespace mimic
