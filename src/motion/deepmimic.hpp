#pragma once
// DeepMimic's character JSON (skeleton, bodies, PD gains) and motion txt. DeepMimic is Y up with
// the character facing +X; everything is converted to mimic's Z-up, X-forward frame on import
// and back on export. Euler "AttachTheta" angles are DeepMimic's Rz*Ry*Rx. Motions whose frames
// have unequal durations are resampled to the shortest one (linear root, slerp rotations).
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "motion/clip.hpp"

namespace mimic {

// A rigid body of a DeepMimic character, attached to the joint of the same index.
struct BodyDef {
  std::string name;
  std::string shape;             // "sphere", "capsule", "box", ...
  double mass = 0.0;             // kg
  Vec3 pos = Vec3::Zero();       // centre in the joint's frame (mimic axes)
  Quat rot = Quat::Identity();   // orientation in the joint's frame (mimic axes)
  // Full extents in the body's frame, mimic axes: box (x, y, z); capsule: diameter in x and y,
  // cylinder length (without caps) in z; sphere: diameter in all three.
  Vec3 size = Vec3::Zero();
  int collision_group = 0;
  bool fall_contact = false;     // touching the ground with this body ends an episode
  Eigen::Vector4d color = Eigen::Vector4d::Ones();
};

struct PdGain {
  double kp = 0.0;
  double kd = 0.0;
};

struct DeepMimicCharacter {
  Skeleton skeleton;
  std::vector<BodyDef> bodies;  // may be empty
};

// The rotation from DeepMimic's axes to mimic's.
Quat deepmimic_to_mimic();

DeepMimicCharacter parse_deepmimic_character(std::string_view text, const std::string& source);
DeepMimicCharacter load_deepmimic_character(const std::filesystem::path& path);

// PD gains per joint (index = joint index) from a DeepMimic controller file.
std::vector<PdGain> parse_deepmimic_pd_gains(std::string_view text, const std::string& source, const Skeleton& sk);

Clip parse_deepmimic_motion(std::string_view text, const std::string& source, const Skeleton& sk);
Clip load_deepmimic_motion(const std::filesystem::path& path, const Skeleton& sk);

// DeepMimic motion text of a clip (its skeleton must have DeepMimic's joint types).
std::string write_deepmimic_motion(const Clip& clip);

// The character file a DeepMimic motion belongs to, found by naming convention: for
// ".../motions/humanoid3d_walk.txt", ".../characters/humanoid3d.txt". Empty if absent.
std::filesystem::path guess_deepmimic_character(const std::filesystem::path& motion_path);

}  // namespace mimic
