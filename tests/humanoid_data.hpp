#pragma once
// DeepMimic's humanoid and its clips from the shared data, for tests that skip without it.
#include <cmath>
#include <memory>

#include "motion/deepmimic.hpp"
#include "sim/character_model.hpp"
#include "test_data.hpp"

namespace mimic::test {

inline CharacterModel humanoid3d() {
  const auto dir = shared_data() / "deepmimic/characters";
  return CharacterModel::from_deepmimic(dir / "humanoid3d.txt", dir / "humanoid3d_ctrl.txt");
}

inline std::shared_ptr<const Clip> humanoid3d_motion(const CharacterModel& ch, const char* name) {
  return std::make_shared<const Clip>(load_deepmimic_motion(shared_data() / "deepmimic/motions" / name, ch.skeleton));
}

// `pose` with every revolute joint (knees, elbows) at the end of its range farther from zero:
// held as PD targets, the humanoid crumples onto its folded legs.
inline Pose folded(const CharacterModel& ch, Pose pose) {
  for (std::size_t j = 0; j < ch.skeleton.joints.size(); ++j) {
    const Joint& joint = ch.skeleton.joints[j];
    if (joint.type != JointType::Revolute || joint.limits.empty()) continue;
    const auto [lo, hi] = joint.limits[0];
    pose.rot[j] = Quat(Eigen::AngleAxisd(std::abs(lo) > std::abs(hi) ? lo : hi, joint.axis));
  }
  return pose;
}

}  // namespace mimic::test

// Skips the calling test unless the humanoid's character file is there.
#define MIMIC_NEED_HUMANOID()                \
  std::filesystem::path mimic_humanoid_path_; \
  MIMIC_REQUIRE_SHARED("deepmimic/characters/humanoid3d.txt", mimic_humanoid_path_)
