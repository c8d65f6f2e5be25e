#include "control/pose_matching.hpp"

#include <algorithm>
#include <limits>

#include "core/error.hpp"
#include "motion/kinematics.hpp"

namespace mimic {

namespace {

std::vector<Vec3> local_joints(const Skeleton& sk, const Pose& pose, MatchHeights heights) {
  const LinkFrames f = forward_kinematics(sk, pose);
  const HeadingFrame h = HeadingFrame::of(pose);
  const Vec3 drop(0, 0, heights == MatchHeights::RootRelative ? pose.root_pos.z() : 0.0);
  std::vector<Vec3> out;
  out.reserve(f.joint_pos.size());
  for (const Vec3& p : f.joint_pos) out.push_back(h.to_local(p) - drop);
  return out;
}

double mean_distance(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double sum = 0.0;
  for (std::size_t j = 0; j < a.size(); ++j) sum += (a[j] - b[j]).norm();
  return sum / static_cast<double>(a.size());
}

}  // namespace

PoseMatcher::PoseMatcher(const std::vector<const Clip*>& clips, MatchHeights heights) : heights_(heights) {
  if (!clips.empty()) skeleton_ = clips.front()->skeleton;
  for (std::size_t i = 0; i < clips.size(); ++i)
    for (std::size_t f = 0; f < clips[i]->frames.size(); ++f) {
      frames_.push_back(local_joints(clips[i]->skeleton, clips[i]->frames[f], heights_));
      where_.push_back({static_cast<int>(i), static_cast<int>(f), 0.0});
    }
  if (frames_.empty()) throw Error("pose matching: the clips have no frame");
  std::vector<Vec3> mean(frames_.front().size(), Vec3::Zero());
  for (const auto& f : frames_)
    for (std::size_t j = 0; j < f.size(); ++j) mean[j] += f[j] / static_cast<double>(frames_.size());
  double sum = 0.0;
  for (const auto& f : frames_) sum += mean_distance(f, mean);
  spread_ = std::max(1e-6, sum / static_cast<double>(frames_.size()));
}

FrameMatch PoseMatcher::nearest(const Pose& pose) const {
  if (pose.rot.size() != skeleton_.joints.size())
    throw Error("pose matching: a pose of " + std::to_string(pose.rot.size()) + " joints against clips of " +
                std::to_string(skeleton_.joints.size()) + " (another skeleton)");
  const std::vector<Vec3> now = local_joints(skeleton_, pose, heights_);
  FrameMatch best{0, 0, std::numeric_limits<double>::infinity()};
  for (std::size_t i = 0; i < frames_.size(); ++i)
    if (const double d = mean_distance(now, frames_[i]); d < best.distance) best = {where_[i].clip, where_[i].frame, d};
  return best;
}

}  // namespace mimic
