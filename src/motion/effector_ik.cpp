#include "motion/effector_ik.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "motion/kinematics.hpp"

namespace mimic {

std::vector<bool> stance_frames(const std::vector<Vec3>& position, double fps, double height, double speed) {
  const std::size_t n = position.size();
  std::vector<bool> stance(n, false);
  if (n == 0) return stance;
  double lowest = position[0].z();
  for (const Vec3& p : position) lowest = std::min(lowest, p.z());
  for (std::size_t f = 0; f < n; ++f) {
    const std::size_t a = f == 0 ? 0 : f - 1, b = std::min(n - 1, f + 1);
    const double dt = static_cast<double>(b - a) / fps;
    const double v = dt > 0 ? (position[b] - position[a]).head<2>().norm() / dt : 0.0;
    stance[f] = position[f].z() - lowest <= height && v <= speed;
  }
  return stance;
}

void hold_stance(std::vector<Vec3>& position, const std::vector<bool>& stance) {
  for (std::size_t f = 0; f < position.size();) {
    if (!stance[f]) {
      ++f;
      continue;
    }
    std::size_t end = f;
    Vec3 sum = Vec3::Zero();
    double lowest = position[f].z();
    for (; end < position.size() && stance[end]; ++end) sum += position[end], lowest = std::min(lowest, position[end].z());
    const Vec3 held(sum.x() / static_cast<double>(end - f), sum.y() / static_cast<double>(end - f), lowest);
    for (; f < end; ++f) position[f] = held;
  }
}

double stance_sliding(const std::vector<Vec3>& position, const std::vector<bool>& stance, double fps) {
  double sum = 0.0;
  int count = 0;
  for (std::size_t f = 0; f + 1 < position.size(); ++f) {
    if (!stance[f] || !stance[f + 1]) continue;
    sum += (position[f + 1] - position[f]).head<2>().norm() * fps;
    ++count;
  }
  return count ? sum / count : 0.0;
}

namespace {

// One unknown of the solve: the root's position along an axis, or a joint's rotation about an
// axis of its own frame.
struct Unknown {
  int joint = -1;  // -1: the root's position
  Vec3 axis = Vec3::Zero();
};

void apply(Pose& pose, const Unknown& u, double amount) {
  if (u.joint < 0) {
    pose.root_pos += amount * u.axis;
    return;
  }
  auto& q = pose.rot[static_cast<std::size_t>(u.joint)];
  q = (q * Quat(Eigen::AngleAxisd(amount, u.axis))).normalized();
}

// A revolute joint kept within its limits, or, without limits, on the side it bends to in the
// clip (a knee does not bend backwards because a goal pulls it).
struct Bound {
  int joint = 0;
  Vec3 axis = Vec3::UnitZ();
  double lo = 0.0, hi = 0.0;
};

void clamp(Pose& pose, const Bound& b) {
  auto& q = pose.rot[static_cast<std::size_t>(b.joint)];
  const double angle = twist_angle(q, b.axis);
  const double kept = std::clamp(angle, b.lo, b.hi);
  if (kept != angle) q = Quat(Eigen::AngleAxisd(kept, b.axis));
}

}  // namespace

double reach_effectors(const Skeleton& sk, std::vector<Pose>& frames, const std::vector<EffectorGoal>& goals, double root_weight) {
  if (goals.empty() || frames.empty()) return 0.0;
  const int nj = sk.num_joints();
  // The joints each goal may move: its ancestors below the root that no other goal's chain shares.
  std::vector<int> goals_below(static_cast<std::size_t>(nj), 0);
  for (const EffectorGoal& g : goals) {
    if (g.joint <= 0 || g.joint >= nj) throw Error("inverse kinematics: goal joint " + std::to_string(g.joint) + " is not a limb joint");
    if (g.position.size() != frames.size()) throw Error("inverse kinematics: a goal has another number of frames than the clip");
    for (int j = sk.joints[static_cast<std::size_t>(g.joint)].parent; j > 0; j = sk.joints[static_cast<std::size_t>(j)].parent)
      ++goals_below[static_cast<std::size_t>(j)];
  }
  std::vector<Unknown> unknowns{{-1, Vec3::UnitX()}, {-1, Vec3::UnitY()}, {-1, Vec3::UnitZ()}};
  std::vector<Bound> bounds;
  for (int j = 1; j < nj; ++j) {
    const Joint& joint = sk.joints[static_cast<std::size_t>(j)];
    if (goals_below[static_cast<std::size_t>(j)] != 1) continue;
    if (joint.type == JointType::Spherical) {
      for (int k = 0; k < 3; ++k) unknowns.push_back({j, Vec3::Unit(k)});
    } else if (joint.type == JointType::Revolute) {
      unknowns.push_back({j, joint.axis});
      Bound b{j, joint.axis, 0.0, 0.0};
      if (!joint.limits.empty()) {
        b.lo = joint.limits[0].first, b.hi = joint.limits[0].second;
      } else {
        double mean = 0.0;
        for (const Pose& p : frames) mean += twist_angle(p.rot[static_cast<std::size_t>(j)], joint.axis);
        const double big = 4.0 * std::acos(0.0);
        b.lo = mean < 0 ? -big : 0.0, b.hi = mean < 0 ? 0.0 : big;
      }
      bounds.push_back(b);
    }
  }
  // moves[c][g]: whether unknown c moves goal g (the root's position moves every goal).
  std::vector<std::vector<bool>> moves(unknowns.size(), std::vector<bool>(goals.size(), true));
  for (std::size_t c = 0; c < unknowns.size(); ++c) {
    if (unknowns[c].joint < 0) continue;
    for (std::size_t g = 0; g < goals.size(); ++g) {
      bool below = false;
      for (int j = sk.joints[static_cast<std::size_t>(goals[g].joint)].parent; j > 0 && !below; j = sk.joints[static_cast<std::size_t>(j)].parent)
        below = j == unknowns[c].joint;
      moves[c][g] = below;
    }
  }
  const auto rows = static_cast<Eigen::Index>(3 * goals.size() + 3), cols = static_cast<Eigen::Index>(unknowns.size());
  constexpr double kDamping = 0.02, kTolerance = 1e-4;
  constexpr int kIterations = 30;
  LinkFrames fk;
  Eigen::VectorXd residual(rows);
  Eigen::MatrixXd jacobian(rows, cols);
  double worst = 0.0;
  for (std::size_t f = 0; f < frames.size(); ++f) {
    Pose& pose = frames[f];
    const Vec3 root_start = pose.root_pos;
    // residual: goal minus reached, per goal; and the root's pull back to where it was.
    auto update = [&] {
      forward_kinematics(sk, pose, fk);
      for (std::size_t g = 0; g < goals.size(); ++g)
        residual.segment<3>(static_cast<Eigen::Index>(3 * g)) = goals[g].position[f] - fk.joint_pos[static_cast<std::size_t>(goals[g].joint)];
      residual.tail<3>() = root_weight * (root_start - pose.root_pos);
    };
    for (int it = 0; it < kIterations; ++it) {
      update();
      double largest = 0.0;
      for (std::size_t g = 0; g < goals.size(); ++g) largest = std::max(largest, residual.segment<3>(static_cast<Eigen::Index>(3 * g)).norm());
      if (largest < kTolerance) break;
      // d(reached)/d(unknown): a rotation about world axis w at joint j moves a point p below it
      // by w x (p - p_j); the root's position moves every goal with it.
      jacobian.setZero();
      for (Eigen::Index c = 0; c < cols; ++c) {
        const Unknown& u = unknowns[static_cast<std::size_t>(c)];
        if (u.joint < 0) jacobian.block<3, 1>(rows - 3, c) = root_weight * u.axis;
        const Vec3 world_axis = u.joint < 0 ? u.axis : Vec3(fk.joint_rot[static_cast<std::size_t>(u.joint)] * u.axis);
        for (std::size_t g = 0; g < goals.size(); ++g) {
          if (!moves[static_cast<std::size_t>(c)][g]) continue;
          const Vec3 p = fk.joint_pos[static_cast<std::size_t>(goals[g].joint)];
          jacobian.block<3, 1>(static_cast<Eigen::Index>(3 * g), c) =
              u.joint < 0 ? u.axis : Vec3(world_axis.cross(p - fk.joint_pos[static_cast<std::size_t>(u.joint)]));
        }
      }
      const Eigen::MatrixXd jjt = jacobian * jacobian.transpose() + kDamping * kDamping * Eigen::MatrixXd::Identity(rows, rows);
      const Eigen::VectorXd step = jacobian.transpose() * jjt.ldlt().solve(residual);
      for (Eigen::Index c = 0; c < cols; ++c) apply(pose, unknowns[static_cast<std::size_t>(c)], step[c]);
      for (const Bound& b : bounds) clamp(pose, b);
    }
    for (std::size_t j = 1; j < pose.rot.size(); ++j) pose.rot[j] = canonical(pose.rot[j]);
    update();
    for (std::size_t g = 0; g < goals.size(); ++g) worst = std::max(worst, residual.segment<3>(static_cast<Eigen::Index>(3 * g)).norm());
  }
  return worst;
}

}  // namespace mimic
