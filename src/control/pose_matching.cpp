#include "control/pose_matching.hpp"

#include <algorithm>
#include <limits>

#include "core/error.hpp"
#include "motion/kinematics.hpp"

namespace mimic {

namespace {

std::vector<Vec3> local_joints(const Skeleton& sk, const Pose& pose) {
  const LinkFrames f = forward_kinematics(sk, pose);
  const HeadingFrame h = HeadingFrame::of(pose);
  std::vector<Vec3> out;
  out.reserve(f.joint_pos.size());
  for (const Vec3& p : f.joint_pos) out.push_back(h.to_local(p));
  return out;
}

double mean_distance(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double sum = 0.0;
  for (std::size_t j = 0; j < a.size(); ++j) sum += (a[j] - b[j]).norm();
  return sum / static_cast<double>(a.size());
}

}  // namespace

PoseMatcher::PoseMatcher(const std::vector<const Clip*>& clips) {
  if (!clips.empty()) skeleton_ = clips.front()->skeleton;
  for (const Clip* c : clips)
    for (const Pose& p : c->frames) frames_.push_back(local_joints(c->skeleton, p));
  if (frames_.empty()) throw Error("pose matching: the clips have no frame");
  std::vector<Vec3> mean(frames_.front().size(), Vec3::Zero());
  for (const auto& f : frames_)
    for (std::size_t j = 0; j < f.size(); ++j) mean[j] += f[j] / static_cast<double>(frames_.size());
  double sum = 0.0;
  for (const auto& f : frames_) sum += mean_distance(f, mean);
  spread_ = std::max(1e-6, sum / static_cast<double>(frames_.size()));
}

double PoseMatcher::cost(const Pose& pose) const {
  const std::vector<Vec3> now = local_joints(skeleton_, pose);
  double best = std::numeric_limits<double>::infinity();
  for (const auto& f : frames_) best = std::min(best, mean_distance(now, f));
  return best;
}

}  // namespace mimic
