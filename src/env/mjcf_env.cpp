#include "env/mjcf_env.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>

#include "core/error.hpp"
#include "sim/mujoco_load.hpp"

namespace mimic {

MjcfEnv::MjcfEnv(std::string name, const std::string& mjcf, int frame_skip, double timestep)
    : name_(std::move(name)), frame_skip_(frame_skip) {
  if (frame_skip < 1) throw Error("environment '" + name_ + "': frame_skip must be >= 1");
  if (timestep < 0 || !std::isfinite(timestep)) throw Error("environment '" + name_ + "': timestep must be positive");
  m_ = compile_mjcf(mjcf, "environment '" + name_ + "'");
  if (timestep > 0) m_->opt.timestep = timestep;
  d_ = mj_makeData(m_);
  if (!d_) {
    mj_deleteModel(m_);
    throw Error("environment '" + name_ + "': MuJoCo cannot allocate its data");
  }
  mj_forward(m_, d_);
}

MjcfEnv::~MjcfEnv() {
  if (d_) mj_deleteData(d_);
  if (m_) mj_deleteModel(m_);
}

int MjcfEnv::action_size() const { return m_->nu; }
double MjcfEnv::physics_dt() const { return m_->opt.timestep; }
double MjcfEnv::time() const { return d_->time; }

Eigen::VectorXd MjcfEnv::qpos() const { return Eigen::Map<const Eigen::VectorXd>(d_->qpos, m_->nq); }
Eigen::VectorXd MjcfEnv::qvel() const { return Eigen::Map<const Eigen::VectorXd>(d_->qvel, m_->nv); }

void MjcfEnv::set_state(const Eigen::VectorXd& qpos, const Eigen::VectorXd& qvel) {
  if (qpos.size() != m_->nq || qvel.size() != m_->nv)
    throw Error("environment '" + name_ + "': set_state needs " + std::to_string(m_->nq) + " positions and " +
                std::to_string(m_->nv) + " velocities, got " + std::to_string(qpos.size()) + " and " + std::to_string(qvel.size()));
  Eigen::Map<Eigen::VectorXd>(d_->qpos, m_->nq) = qpos;
  Eigen::Map<Eigen::VectorXd>(d_->qvel, m_->nv) = qvel;
  mj_forward(m_, d_);
}

int MjcfEnv::body_id(const std::string& body) const {
  const int id = mj_name2id(m_, mjOBJ_BODY, body.c_str());
  if (id < 0) throw Error("environment '" + name_ + "' has no body named '" + body + "'");
  return id;
}

int MjcfEnv::site_id(const std::string& site) const {
  const int id = mj_name2id(m_, mjOBJ_SITE, site.c_str());
  if (id < 0) throw Error("environment '" + name_ + "' has no site named '" + site + "'");
  return id;
}

Eigen::Vector3d MjcfEnv::body_pos(int body) const {
  if (body < 0 || body >= m_->nbody) throw Error("environment '" + name_ + "': body id out of range");
  return Eigen::Map<const Eigen::Vector3d>(d_->xpos + 3 * body);
}

Eigen::Vector3d MjcfEnv::site_pos(int site) const {
  if (site < 0 || site >= m_->nsite) throw Error("environment '" + name_ + "': site id out of range");
  return Eigen::Map<const Eigen::Vector3d>(d_->site_xpos + 3 * site);
}

Eigen::VectorXd MjcfEnv::clip_action(const Eigen::VectorXd& action) const {
  if (action.size() != m_->nu)
    throw Error("environment '" + name_ + "': action has " + std::to_string(action.size()) + " entries, expected " + std::to_string(m_->nu));
  if (!action.allFinite()) throw Error("environment '" + name_ + "': action has a non-finite entry");
  Eigen::VectorXd u = action;
  for (int i = 0; i < m_->nu; ++i) {
    if (!m_->actuator_ctrllimited[i]) continue;
    u[i] = std::clamp(u[i], m_->actuator_ctrlrange[2 * i], m_->actuator_ctrlrange[2 * i + 1]);
  }
  return u;
}

void MjcfEnv::reset_data() {
  mj_resetData(m_, d_);
  mj_forward(m_, d_);
}

Eigen::VectorXd MjcfEnv::simulate(const Eigen::VectorXd& action) {
  const Eigen::VectorXd u = clip_action(action);
  Eigen::Map<Eigen::VectorXd>(d_->ctrl, m_->nu) = u;
  // MuJoCo silently resets the state when the integration blows up; say so instead.
  const int bad[] = {mjWARN_BADQPOS, mjWARN_BADQVEL, mjWARN_BADQACC};
  for (int w : bad) d_->warning[w].number = 0;
  const double t0 = d_->time;
  for (int s = 0; s < frame_skip_; ++s) mj_step(m_, d_);
  for (int w : bad)
    if (d_->warning[w].number > 0)
      throw Error("environment '" + name_ + "': the simulation diverged after t = " + std::to_string(t0) + " s");
  // mj_step leaves positions computed for the state before its last integration.
  mj_kinematics(m_, d_);
  return u;
}

}  // namespace mimic
