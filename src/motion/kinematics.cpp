#include "motion/kinematics.hpp"

#include <algorithm>
#include <limits>

namespace mimic {

void forward_kinematics(const Skeleton& sk, const Pose& pose, LinkFrames& out) {
  const std::size_t n = sk.joints.size();
  out.joint_pos.resize(n);
  out.joint_rot.resize(n);
  out.joint_pos[0] = pose.root_pos;
  out.joint_rot[0] = pose.rot[0];
  for (std::size_t j = 1; j < n; ++j) {
    const Joint& jt = sk.joints[j];
    const auto p = static_cast<std::size_t>(jt.parent);
    out.joint_pos[j] = out.joint_pos[p] + out.joint_rot[p] * jt.offset;
    out.joint_rot[j] = out.joint_rot[p] * jt.rest * pose.rot[j];
  }
  out.site_pos.resize(sk.sites.size());
  for (std::size_t s = 0; s < sk.sites.size(); ++s) {
    const auto j = static_cast<std::size_t>(sk.sites[s].joint);
    out.site_pos[s] = out.joint_pos[j] + out.joint_rot[j] * sk.sites[s].offset;
  }
}

LinkFrames forward_kinematics(const Skeleton& sk, const Pose& pose) {
  LinkFrames out;
  forward_kinematics(sk, pose, out);
  return out;
}

std::vector<PoseVelocity> clip_velocities(const Clip& clip) {
  const int n = clip.num_frames();
  const std::size_t nj = clip.skeleton.joints.size();
  std::vector<PoseVelocity> out(static_cast<std::size_t>(n));
  if (n < 2) {
    for (auto& v : out) v.joint_ang.assign(nj, Vec3::Zero());
    return out;
  }
  const double dt = 1.0 / clip.fps;
  const bool wrap = clip.loop == LoopMode::Wrap;
  for (int i = 0; i < n; ++i) {
    // Neighbouring poses; Clip::sample handles the seam of wrap clips.
    const bool has_prev = i > 0 || wrap;
    const bool has_next = i < n - 1 || wrap;
    const Pose& cur = clip.frames[static_cast<std::size_t>(i)];
    const Pose prev = has_prev ? (i > 0 ? clip.frames[static_cast<std::size_t>(i - 1)] : clip.sample(-dt)) : cur;
    const Pose next = has_next ? (i < n - 1 ? clip.frames[static_cast<std::size_t>(i + 1)] : clip.sample((i + 1) * dt)) : cur;
    const double span = dt * ((has_prev ? 1 : 0) + (has_next ? 1 : 0));
    out[static_cast<std::size_t>(i)] = pose_velocity(prev, next, span);
  }
  return out;
}

PoseVelocity pose_velocity(const Pose& a, const Pose& b, double dt) {
  PoseVelocity v;
  v.root_lin = (b.root_pos - a.root_pos) / dt;
  v.root_ang = angular_velocity(a.rot[0], b.rot[0], dt);
  v.joint_ang.assign(a.rot.size(), Vec3::Zero());
  for (std::size_t j = 1; j < a.rot.size(); ++j) {
    // Local frame: b = a * exp(w * dt).
    v.joint_ang[j] = quat_to_rotvec(a.rot[j].conjugate() * b.rot[j]) / dt;
  }
  return v;
}

std::vector<double> peak_joint_speeds(const Clip& clip) {
  std::vector<double> peak(clip.skeleton.joints.size(), 0.0);
  for (std::size_t f = 1; f < clip.frames.size(); ++f) {
    const PoseVelocity v = pose_velocity(clip.frames[f - 1], clip.frames[f], 1.0 / clip.fps);
    for (std::size_t j = 1; j < peak.size(); ++j) peak[j] = std::max(peak[j], v.joint_ang[j].norm());
  }
  return peak;
}

std::pair<Pose, PoseVelocity> clip_state(const Clip& clip, double t) {
  const double h = 1.0 / clip.fps;  // as clip_velocities: at frame times the two agree
  double t0 = t - h, t1 = t + h;
  if (clip.loop != LoopMode::Wrap) {  // stay inside the clip
    t0 = std::clamp(t0, 0.0, std::max(0.0, clip.duration() - 2 * h));
    t1 = t0 + 2 * h;
  }
  return {clip.sample(t), pose_velocity(clip.sample(t0), clip.sample(t1), t1 - t0)};
}

HeadingFrame HeadingFrame::of(const Pose& pose) {
  HeadingFrame h;
  h.origin = Vec3(pose.root_pos.x(), pose.root_pos.y(), 0.0);
  h.yaw = heading_rotation(heading_angle(pose.rot[0]));
  return h;
}

double clip_min_height(const Clip& clip) {
  double lo = std::numeric_limits<double>::infinity();
  LinkFrames fk;
  for (const Pose& p : clip.frames) {
    forward_kinematics(clip.skeleton, p, fk);
    for (const Vec3& x : fk.joint_pos) lo = std::min(lo, x.z());
    for (const Vec3& x : fk.site_pos) lo = std::min(lo, x.z());
  }
  return lo;
}

}  // namespace mimic
