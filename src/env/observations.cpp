#include "env/observations.hpp"

#include <mujoco/mujoco.h>

#include <cmath>

#include "core/error.hpp"

namespace mimic {
namespace {

const std::vector<std::string> kKnown = {"full_state", "egocentric", "links", "link_velocities", "phase", "reference_root", "height_map"};

// Appends to `out` at `k` (a running index).
struct Writer {
  Eigen::VectorXd& out;
  Eigen::Index k = 0;
  void put(double v) { out[k++] = v; }
  void put(const Vec3& v) { put(v.x()), put(v.y()), put(v.z()); }
  void put(const Quat& q) {
    const Quat c = canonical(q);
    put(c.w()), put(c.x()), put(c.y()), put(c.z());
  }
};

}  // namespace

ObservationBuilder::ObservationBuilder(const World& world, const ObservationConfig& cfg, bool has_reference)
    : cfg_(cfg), skeleton_(world.character().skeleton) {
  const mjModel* m = world.model();
  for (const Joint& jt : skeleton_.joints) {
    const int jid = mj_name2id(m, mjOBJ_JOINT, jt.name.c_str());
    dof_.push_back(jid < 0 ? -1 : m->jnt_dofadr[jid]);
    body_.push_back(mj_name2id(m, mjOBJ_BODY, jt.name.c_str()));
  }
  if (cfg.names.empty()) throw Error("observations: at least one observation must be named");
  if (cfg.link_history < 1 || cfg.link_history > 64) throw Error("observations: link_history must be 1..64");
  if (cfg.height_map_size < 1 || cfg.height_map_size > 256 || !(cfg.height_map_spacing > 0) || !std::isfinite(cfg.height_map_ahead))
    throw Error("observations: height_map_size must be 1..256 and height_map_spacing positive");
  // Egocentric points: end effectors and the highest joint at rest (the head).
  const LinkFrames rest = forward_kinematics(skeleton_, rest_pose(skeleton_));
  int head = 0;
  for (int j = 0; j < skeleton_.num_joints(); ++j) {
    if (skeleton_.joints[static_cast<std::size_t>(j)].end_effector) ego_points_.push_back(j);
    if (rest.joint_pos[static_cast<std::size_t>(j)].z() > rest.joint_pos[static_cast<std::size_t>(head)].z()) head = j;
  }
  if (std::find(ego_points_.begin(), ego_points_.end(), head) == ego_points_.end()) ego_points_.push_back(head);
  for (const std::string& name : cfg.names) {
    if (std::find(kKnown.begin(), kKnown.end(), name) == kKnown.end()) {
      std::string known;
      for (const auto& k : kKnown) known += (known.empty() ? "" : ", ") + k;
      throw Error("observations: unknown observation '" + name + "' (known: " + known + ")");
    }
    if ((name == "phase" || name == "reference_root") && !has_reference)
      throw Error("observations: '" + name + "' needs a reference clip");
    layout_.push_back(ObservationSlice{name, size_, part_size(name)});
    size_ += layout_.back().size;
  }
}

int ObservationBuilder::part_size(const std::string& name) const {
  const int nj = skeleton_.num_joints();
  if (name == "full_state") {
    int n = 1 + 4 + 3 + 3;
    for (const Joint& j : skeleton_.joints) {
      if (j.type == JointType::Spherical) n += 4 + 3;
      if (j.type == JointType::Revolute) n += 1 + 1;
    }
    return n;
  }
  if (name == "egocentric") return 9 + 3 * static_cast<int>(ego_points_.size());
  if (name == "links") return cfg_.link_history * 7 * nj;
  if (name == "link_velocities") return 6 * nj;
  if (name == "height_map") return cfg_.height_map_size * cfg_.height_map_size;
  if (name == "reference_root") return 3;
  return 1;  // phase
}

Vec3 ObservationBuilder::height_map_point(const HeadingFrame& heading, int i, int j) const {
  const double c = 0.5 * (cfg_.height_map_size - 1);
  const Vec3 local(cfg_.height_map_ahead + (i - c) * cfg_.height_map_spacing, (j - c) * cfg_.height_map_spacing, 0.0);
  return heading.origin + heading.yaw * local;
}

void ObservationBuilder::build(const ObservationContext& ctx, Eigen::VectorXd& out) const {
  out.resize(size_);
  Writer w{out};
  const World& world = *ctx.world;
  const Pose pose = world.pose();
  const LinkFrames& now = ctx.history->back();
  const HeadingFrame heading = HeadingFrame::of(pose);
  const mjModel* m = world.model();
  mjData* d = world.data();
  const int root_dof = dof_[0];
  const Vec3 root_lin(d->qvel[root_dof], d->qvel[root_dof + 1], d->qvel[root_dof + 2]);
  const Vec3 root_ang_local(d->qvel[root_dof + 3], d->qvel[root_dof + 4], d->qvel[root_dof + 5]);
  const Quat root = pose.rot[0];
  for (const std::string& name : cfg_.names) {
    if (name == "full_state") {
      w.put(pose.root_pos.z());
      w.put(heading.rot_to_local(root));
      for (std::size_t j = 1; j < skeleton_.joints.size(); ++j) {
        const Joint& jt = skeleton_.joints[j];
        if (jt.type == JointType::Spherical) w.put(pose.rot[j]);
        if (jt.type == JointType::Revolute) w.put(revolute_angle(jt, pose.rot[j]));
      }
      w.put(heading.dir_to_local(root_lin));
      w.put(heading.dir_to_local(root * root_ang_local));
      for (std::size_t j = 1; j < skeleton_.joints.size(); ++j) {
        const Joint& jt = skeleton_.joints[j];
        const int v = dof_[j];
        if (jt.type == JointType::Spherical) w.put(Vec3(d->qvel[v], d->qvel[v + 1], d->qvel[v + 2]));
        if (jt.type == JointType::Revolute) w.put(d->qvel[v]);
      }
    } else if (name == "egocentric") {
      w.put(root.conjugate() * root_lin);  // velocimeter
      w.put(root_ang_local);                // gyro
      w.put(root.conjugate() * Vec3::UnitZ());  // uprightness
      for (int j : ego_points_) w.put(root.conjugate() * (now.joint_pos[static_cast<std::size_t>(j)] - now.joint_pos[0]));
    } else if (name == "links") {
      // Oldest first; frames missing at the start of an episode repeat the oldest one.
      const auto n = static_cast<int>(ctx.history->size());
      for (int k = cfg_.link_history; k >= 1; --k) {
        const LinkFrames& f = (*ctx.history)[static_cast<std::size_t>(std::max(0, n - k))];
        for (std::size_t j = 0; j < f.joint_pos.size(); ++j) {
          w.put(heading.to_local(f.joint_pos[j]));
          w.put(heading.rot_to_local(f.joint_rot[j]));
        }
      }
    } else if (name == "link_velocities") {
      for (const int body : body_) {
        double vel[6];
        mj_objectVelocity(m, d, mjOBJ_BODY, body, vel, 0);
        w.put(heading.dir_to_local(Vec3(vel[3], vel[4], vel[5])));
        w.put(heading.dir_to_local(Vec3(vel[0], vel[1], vel[2])));
      }
    } else if (name == "height_map") {
      for (int i = 0; i < cfg_.height_map_size; ++i)
        for (int j = 0; j < cfg_.height_map_size; ++j) {
          const Vec3 p = height_map_point(heading, i, j);
          w.put((ctx.terrain ? ctx.terrain->height(p.x(), p.y()) : 0.0) - pose.root_pos.z());
        }
    } else if (name == "reference_root") {
      w.put(heading.dir_to_local(ctx.reference->sample(ctx.time).root_pos - pose.root_pos));
    } else {  // phase
      const double dur = ctx.reference->duration();
      w.put(dur > 0 ? std::fmod(std::max(0.0, ctx.time), dur) / dur : 0.0);
    }
  }
}

}  // namespace mimic
