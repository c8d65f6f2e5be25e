#include "video/pose_error.hpp"

#include <cmath>

#include "core/error.hpp"
#include "motion/kinematics.hpp"

namespace mimic {

double jitter(const Clip& clip) {
  if (clip.num_frames() < 3) throw Error(clip.name + ": jitter needs 3 frames at least");
  std::vector<LinkFrames> f(static_cast<std::size_t>(clip.num_frames()));
  for (int i = 0; i < clip.num_frames(); ++i) forward_kinematics(clip.skeleton, clip.frames[static_cast<std::size_t>(i)], f[static_cast<std::size_t>(i)]);
  double sum = 0;
  long count = 0;
  for (std::size_t i = 1; i + 1 < f.size(); ++i)
    for (std::size_t j = 0; j < f[i].joint_pos.size(); ++j, ++count)
      sum += (f[i + 1].joint_pos[j] - 2 * f[i].joint_pos[j] + f[i - 1].joint_pos[j]).norm() * clip.fps * clip.fps;
  return sum / static_cast<double>(count);
}

PoseErrors pose_errors(const Clip& est, const Clip& truth, double truth_start) {
  std::vector<std::pair<int, int>> shared;  // estimate joint, truth joint
  for (int j = 0; j < est.skeleton.num_joints(); ++j)
    if (const int k = truth.skeleton.find(est.skeleton.joints[static_cast<std::size_t>(j)].name); k >= 0) shared.emplace_back(j, k);
  if (shared.size() < 4) throw Error(est.name + " against " + truth.name + ": only " + std::to_string(shared.size()) + " joints share names (4 at least)");
  if (est.num_frames() < 3) throw Error(est.name + ": fewer than 3 frames to measure");
  const auto n = static_cast<std::size_t>(est.num_frames());
  std::vector<std::vector<Vec3>> a(n), b(n);  // root-relative
  for (std::size_t i = 0; i < n; ++i) {
    const LinkFrames fe = forward_kinematics(est.skeleton, est.frames[i]);
    const LinkFrames ft = forward_kinematics(truth.skeleton, truth.sample(truth_start + static_cast<double>(i) / est.fps));
    for (const auto& [je, jt] : shared) {
      a[i].push_back(fe.joint_pos[static_cast<std::size_t>(je)] - fe.joint_pos[0]);
      b[i].push_back(ft.joint_pos[static_cast<std::size_t>(jt)] - ft.joint_pos[0]);
    }
  }
  // One yaw for the clip: argmax Σ b·R(ψ)a over the horizontal components.
  double c = 0, s = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < shared.size(); ++k) {
      c += a[i][k].x() * b[i][k].x() + a[i][k].y() * b[i][k].y();
      s += a[i][k].x() * b[i][k].y() - a[i][k].y() * b[i][k].x();
    }
  const Mat3 yaw = heading_rotation(std::atan2(s, c)).toRotationMatrix();
  PoseErrors e;
  e.frames = static_cast<int>(n), e.joints = static_cast<int>(shared.size());
  for (std::size_t i = 0; i < n; ++i) {
    Eigen::Matrix3Xd pa(3, static_cast<Eigen::Index>(shared.size())), pb(3, static_cast<Eigen::Index>(shared.size()));
    for (std::size_t k = 0; k < shared.size(); ++k) {
      e.mpjpe += (yaw * a[i][k] - b[i][k]).norm();
      pa.col(static_cast<Eigen::Index>(k)) = a[i][k], pb.col(static_cast<Eigen::Index>(k)) = b[i][k];
    }
    const Eigen::Matrix4d t = Eigen::umeyama(pa, pb, true);
    const Eigen::Matrix3Xd aligned = (t.topLeftCorner<3, 3>() * pa).colwise() + t.topRightCorner<3, 1>();
    e.pa_mpjpe += (aligned - pb).colwise().norm().sum();
  }
  const double count = static_cast<double>(n * shared.size());
  e.mpjpe /= count, e.pa_mpjpe /= count;
  e.jitter = jitter(est);
  return e;
}

}  // namespace mimic
