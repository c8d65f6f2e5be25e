#include "sim/world.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "sim/mujoco_load.hpp"
#include "sim/mujoco_state.hpp"

namespace mimic {

World::World(const CharacterModel& ch, const SimConfig& cfg) : World(ch, cfg, MjcfOptions{}) {}

World::World(const CharacterModel& ch, const SimConfig& cfg, MjcfOptions model)
    : World(ch, build_mjcf(ch, [&] { model.timestep = 1.0 / cfg.physics_hz; return model; }()), cfg) {}

World::World(const CharacterModel& ch, const std::string& mjcf, const SimConfig& cfg) : ch_(ch), cfg_(cfg) {
  if (!(cfg.physics_hz > 0) || !(cfg.control_hz > 0) || cfg.control_hz > cfg.physics_hz)
    throw Error("simulation rates: need 0 < control_hz <= physics_hz");
  const double ratio = cfg.physics_hz / cfg.control_hz;
  substeps_ = static_cast<int>(std::lround(ratio));
  if (std::abs(ratio - substeps_) > 1e-6)
    throw Error("simulation rates: physics_hz must be a whole multiple of control_hz");
  init(mjcf);
}

World::~World() {
  if (scratch_) mj_deleteData(scratch_);
  if (d_) mj_deleteData(d_);
  if (m_) mj_deleteModel(m_);
}

void World::init(const std::string& mjcf) {
  m_ = compile_mjcf(mjcf, "'" + ch_.name + "'");
  m_->opt.timestep = 1.0 / cfg_.physics_hz;
  d_ = mj_makeData(m_);
  const Skeleton& sk = ch_.skeleton;
  for (const Joint& j : sk.joints) {
    const int b = mj_name2id(m_, mjOBJ_BODY, j.name.c_str());
    if (b < 0) throw Error("model of '" + ch_.name + "' has no body named '" + j.name + "'");
    body_.push_back(b);
    const int jid = j.type == JointType::Fixed ? -1 : mj_name2id(m_, mjOBJ_JOINT, j.name.c_str());
    if (j.type != JointType::Fixed && jid < 0) throw Error("model of '" + ch_.name + "' has no joint named '" + j.name + "'");
    qpos_.push_back(jid < 0 ? -1 : m_->jnt_qposadr[jid]);
    dof_.push_back(jid < 0 ? -1 : m_->jnt_dofadr[jid]);
  }
  set_targets(std::vector<Quat>(sk.joints.size(), Quat::Identity()));
  mj_forward(m_, d_);
}

double World::time() const { return d_->time; }

namespace {

// The body a contact presses against the world body (the floor, terrain), or -1 for a contact
// between two other bodies: ground_contacts' and ground_penetration's shared test.
int body_against_world(const mjModel* m, const mjContact& con) {
  const int b1 = m->geom_bodyid[con.geom1], b2 = m->geom_bodyid[con.geom2];
  if (b1 == 0 && b2 != 0) return b2;
  if (b2 == 0 && b1 != 0) return b1;
  return -1;
}

// A pose as MuJoCo coordinates in `d` (`qpos` holds each joint's address): set_state's and
// write_pose's shared half.
void write_qpos(const Skeleton& sk, const std::vector<int>& qpos, const Pose& pose, mjData* d) {
  for (std::size_t j = 0; j < sk.joints.size(); ++j) {
    const int a = qpos[j];
    const Quat& q = pose.rot[j];
    switch (sk.joints[j].type) {
      case JointType::Free:
        for (int k = 0; k < 3; ++k) d->qpos[a + k] = pose.root_pos[k];
        d->qpos[a + 3] = q.w(), d->qpos[a + 4] = q.x(), d->qpos[a + 5] = q.y(), d->qpos[a + 6] = q.z();
        break;
      case JointType::Spherical: d->qpos[a] = q.w(), d->qpos[a + 1] = q.x(), d->qpos[a + 2] = q.y(), d->qpos[a + 3] = q.z(); break;
      case JointType::Revolute: d->qpos[a] = revolute_angle(sk.joints[j], q); break;
      case JointType::Fixed: break;
    }
  }
}

// Velocities as MuJoCo's in `d` (`dof` holds each joint's address): set_state's and momentum_of's.
void write_qvel(const Skeleton& sk, const std::vector<int>& dof, const Pose& pose, const PoseVelocity& vel, mjData* d) {
  for (std::size_t j = 0; j < sk.joints.size(); ++j) {
    const int v = dof[j];
    switch (sk.joints[j].type) {
      case JointType::Free: {
        const Vec3 ang_local = pose.rot[j].conjugate() * vel.root_ang;  // MuJoCo: free-joint spin in the body frame
        for (int k = 0; k < 3; ++k) d->qvel[v + k] = vel.root_lin[k], d->qvel[v + 3 + k] = ang_local[k];
        break;
      }
      case JointType::Spherical: for (int k = 0; k < 3; ++k) d->qvel[v + k] = vel.joint_ang[j][k]; break;
      case JointType::Revolute: d->qvel[v] = vel.joint_ang[j].dot(sk.joints[j].axis); break;
      case JointType::Fixed: break;
    }
  }
}

void check_state(const Skeleton& sk, const Pose& pose, const PoseVelocity* vel, const char* who) {
  if (pose.rot.size() != sk.joints.size()) throw Error(std::string(who) + ": pose has the wrong number of joints");
  if (vel && vel->joint_ang.size() != sk.joints.size())
    throw Error(std::string(who) + ": velocities have " + std::to_string(vel->joint_ang.size()) + " joints, the character " +
                std::to_string(sk.joints.size()));
}

}  // namespace

void World::set_state(const Pose& pose, const PoseVelocity* vel) {
  const Skeleton& sk = ch_.skeleton;
  check_state(sk, pose, vel, "set_state");
  reset_state(m_, d_);
  write_qpos(sk, qpos_, pose, d_);
  if (vel) write_qvel(sk, dof_, pose, *vel, d_);
  set_targets(pose.rot);
  mj_forward(m_, d_);
}

BodyMomentum World::momentum_of(const Pose& pose, const PoseVelocity& vel) const {
  const Skeleton& sk = ch_.skeleton;
  check_state(sk, pose, &vel, "momentum_of");
  if (!scratch_) scratch_ = mj_makeData(m_);
  mjData* s = scratch_;
  reset_state(m_, s);
  write_qpos(sk, qpos_, pose, s);
  write_qvel(sk, dof_, pose, vel, s);
  // The smooth-dynamics stages subtree velocities need; no contacts or forces.
  mj_kinematics(m_, s);
  mj_comPos(m_, s);
  mj_comVel(m_, s);
  mj_subtreeVel(m_, s);
  const int root = body_[0];
  const auto vec = [](const mjtNum* v) { return Vec3(v[0], v[1], v[2]); };
  BodyMomentum b;
  b.mass = m_->body_subtreemass[root];
  b.com = vec(s->subtree_com + 3 * root);
  b.com_velocity = vec(s->subtree_linvel + 3 * root);
  b.angular = vec(s->subtree_angmom + 3 * root);
  for (const int body : body_) {  // each body's inertia moved to the centre of mass (parallel axes)
    const Eigen::Map<const Eigen::Matrix<mjtNum, 3, 3, Eigen::RowMajor>> rot(s->ximat + 9 * body);
    const Vec3 r = vec(s->xipos + 3 * body) - b.com;
    const double mass = m_->body_mass[body];
    b.inertia += rot * vec(m_->body_inertia + 3 * body).asDiagonal() * rot.transpose() +
                 mass * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
  }
  return b;
}

Pose World::pose() const {
  const Skeleton& sk = ch_.skeleton;
  Pose p = rest_pose(sk);
  for (std::size_t j = 0; j < sk.joints.size(); ++j) {
    const int a = qpos_[j];
    switch (sk.joints[j].type) {
      case JointType::Free:
        p.root_pos = Vec3(d_->qpos[a], d_->qpos[a + 1], d_->qpos[a + 2]);
        p.rot[j] = Quat(d_->qpos[a + 3], d_->qpos[a + 4], d_->qpos[a + 5], d_->qpos[a + 6]).normalized();
        break;
      case JointType::Spherical:
        p.rot[j] = Quat(d_->qpos[a], d_->qpos[a + 1], d_->qpos[a + 2], d_->qpos[a + 3]).normalized();
        break;
      case JointType::Revolute:
        p.rot[j] = Quat(Eigen::AngleAxisd(d_->qpos[a], sk.joints[j].axis));
        break;
      case JointType::Fixed: break;
    }
  }
  return p;
}

Vec3 World::root_position() const {
  if (ch_.skeleton.joints.front().type != JointType::Free) return pose().root_pos;
  const int a = qpos_.front();
  return Vec3(d_->qpos[a], d_->qpos[a + 1], d_->qpos[a + 2]);
}

void World::write_pose(const Pose& pose, mjData* other) const {
  if (pose.rot.size() != ch_.skeleton.joints.size()) throw Error("write_pose: pose has the wrong number of joints");
  write_qpos(ch_.skeleton, qpos_, pose, other);
  mj_kinematics(m_, other);
}

PoseVelocity World::velocity() const {
  const Skeleton& sk = ch_.skeleton;
  PoseVelocity v;
  v.joint_ang.assign(sk.joints.size(), Vec3::Zero());
  for (std::size_t j = 0; j < sk.joints.size(); ++j) {
    const int a = qpos_[j], k = dof_[j];
    switch (sk.joints[j].type) {
      case JointType::Free: {
        const Quat q(d_->qpos[a + 3], d_->qpos[a + 4], d_->qpos[a + 5], d_->qpos[a + 6]);
        v.root_lin = Vec3(d_->qvel[k], d_->qvel[k + 1], d_->qvel[k + 2]);
        v.root_ang = q.normalized() * Vec3(d_->qvel[k + 3], d_->qvel[k + 4], d_->qvel[k + 5]);
        break;
      }
      case JointType::Spherical: v.joint_ang[j] = Vec3(d_->qvel[k], d_->qvel[k + 1], d_->qvel[k + 2]); break;
      case JointType::Revolute: v.joint_ang[j] = sk.joints[j].axis * d_->qvel[k]; break;
      case JointType::Fixed: break;
    }
  }
  return v;
}

void World::set_pd_targets(const Pose& targets) {
  if (targets.rot.size() != ch_.skeleton.joints.size()) throw Error("set_pd_targets: wrong number of joints");
  set_targets(targets.rot);
}

void World::set_targets(const std::vector<Quat>& rot) {
  // Revolute angles once per control step, not once per physics step.
  target_ = rot;
  target_angle_.assign(rot.size(), 0.0);
  for (std::size_t j = 1; j < rot.size(); ++j)
    if (ch_.skeleton.joints[j].type == JointType::Revolute) target_angle_[j] = revolute_angle(ch_.skeleton.joints[j], rot[j]);
}

void World::apply_pd() {
  // Spring part of PD on the position predicted one step ahead (q + dt * qdot): stable for stiff
  // gains at 600 Hz; the damping part is MuJoCo's joint damping, integrated implicitly.
  const Skeleton& sk = ch_.skeleton;
  const double dt = m_->opt.timestep;
  const bool total = cfg_.pd_limit == PdLimit::Total;
  // One DoF's applied force. Under `Total` the limit bounds spring minus damping, and the damping
  // MuJoCo is about to subtract is added back: below the limit this is the spring alone, as under
  // `Spring`; at the limit the net force is the limit, however fast the joint turns.
  auto force = [&](double spring, double kd, double lim, double qvel) {
    if (!total) return std::clamp(spring, -lim, lim);
    return std::clamp(spring - kd * qvel, -lim, lim) + kd * qvel;
  };
  for (std::size_t j = 1; j < sk.joints.size(); ++j) {
    const Joint& jt = sk.joints[j];
    const int a = qpos_[j], v = dof_[j];
    const double kp = ch_.gains[j].kp, kd = ch_.gains[j].kd, lim = jt.torque_limit > 0 ? jt.torque_limit : 1e9;
    if (jt.type == JointType::Spherical) {
      const Quat q(d_->qpos[a], d_->qpos[a + 1], d_->qpos[a + 2], d_->qpos[a + 3]);
      const Vec3 w(d_->qvel[v], d_->qvel[v + 1], d_->qvel[v + 2]);
      const Quat predicted = (q * rotvec_to_quat(w * dt)).normalized();
      const Vec3 err = quat_to_rotvec(predicted.conjugate() * target_[j]);
      for (int k = 0; k < 3; ++k) d_->qfrc_applied[v + k] = force(kp * err[k], kd, lim, w[k]);
    } else if (jt.type == JointType::Revolute) {
      const double predicted = d_->qpos[a] + dt * d_->qvel[v];
      const double err = target_angle_[j] - predicted;
      d_->qfrc_applied[v] = force(kp * err, kd, lim, d_->qvel[v]);
    }
  }
}

void World::step() {
  for (int s = 0; s < substeps_; ++s) {
    apply_pd();
    mj_step(m_, d_);
  }
}

void World::step_limp() {
  const Skeleton& sk = ch_.skeleton;
  for (std::size_t j = 1; j < sk.joints.size(); ++j) {
    const int dofs = sk.joints[j].type == JointType::Spherical ? 3 : sk.joints[j].type == JointType::Revolute ? 1 : 0;
    for (int k = 0; k < dofs; ++k) d_->qfrc_applied[dof_[j] + k] = 0.0;
  }
  for (int s = 0; s < substeps_; ++s) mj_step(m_, d_);
}

LinkFrames World::link_frames() const {
  const Skeleton& sk = ch_.skeleton;
  LinkFrames out;
  out.joint_pos.resize(sk.joints.size());
  out.joint_rot.resize(sk.joints.size());
  for (std::size_t j = 0; j < sk.joints.size(); ++j) {
    const int b = body_[j];
    out.joint_pos[j] = Vec3(d_->xpos[3 * b], d_->xpos[3 * b + 1], d_->xpos[3 * b + 2]);
    out.joint_rot[j] = Quat(d_->xquat[4 * b], d_->xquat[4 * b + 1], d_->xquat[4 * b + 2], d_->xquat[4 * b + 3]);
  }
  out.site_pos.resize(sk.sites.size());
  for (std::size_t s = 0; s < sk.sites.size(); ++s) {
    const auto j = static_cast<std::size_t>(sk.sites[s].joint);
    out.site_pos[s] = out.joint_pos[j] + out.joint_rot[j] * sk.sites[s].offset;
  }
  return out;
}

Vec3 World::centre_of_mass() const {
  const int root = body_[0];
  return Vec3(d_->subtree_com[3 * root], d_->subtree_com[3 * root + 1], d_->subtree_com[3 * root + 2]);
}

std::vector<bool> World::ground_contacts() const { return contacts_with_world(d_); }

std::vector<bool> World::contacts_with_world(const mjData* d) const {
  std::vector<bool> touching(ch_.skeleton.joints.size(), false);
  for (int c = 0; c < d->ncon; ++c) {
    const int other = body_against_world(m_, d->contact[c]);
    for (std::size_t j = 0; j < body_.size(); ++j)
      if (other >= 0 && body_[j] == other) touching[j] = true;
  }
  return touching;
}

std::vector<bool> World::ground_contacts_of(const Pose& pose, double gap) const {
  if (pose.rot.size() != ch_.skeleton.joints.size()) throw Error("ground_contacts_of: pose has the wrong number of joints");
  if (!scratch_) scratch_ = mj_makeData(m_);
  mjData* s = scratch_;
  reset_state(m_, s);
  Pose lowered = pose;
  lowered.root_pos.z() -= gap;  // within `gap` of the floor: into it
  write_qpos(ch_.skeleton, qpos_, lowered, s);
  mj_kinematics(m_, s);
  mj_collision(m_, s);
  return contacts_with_world(s);
}

double World::ground_penetration() const {
  double depth = 0.0;
  for (int c = 0; c < d_->ncon; ++c) {
    const mjContact& con = d_->contact[c];
    const int other = body_against_world(m_, con);
    if (other < 0 || std::find(body_.begin(), body_.end(), other) == body_.end()) continue;  // a projectile's
    depth = std::max(depth, -static_cast<double>(con.dist));
  }
  return depth;
}

}  // namespace mimic
