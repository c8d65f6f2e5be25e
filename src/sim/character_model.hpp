#pragma once
// A simulated character: its skeleton, rigid bodies and PD gains, and the MuJoCo model (MJCF)
// generated from them. Models are generated, never hand-copied.
#include <filesystem>
#include <string>
#include <vector>

#include "motion/deepmimic.hpp"

namespace mimic {

struct CharacterModel {
  std::string name;
  Skeleton skeleton;
  std::vector<BodyDef> bodies;  // one per joint (index = joint index)
  std::vector<PdGain> gains;    // one per joint; root's unused

  // From DeepMimic's character file and, optionally, its PD-controller file (else default gains).
  static CharacterModel from_deepmimic(const std::filesystem::path& character, const std::filesystem::path& controller = {});
  // A simple body for any skeleton (BVH, ASF, .mclip): per joint a capsule along the bone to its
  // first child or site (radius 4 cm, 1000 kg/m^3 over a 6 cm-wide limb), gains from its size.
  static CharacterModel from_skeleton(const Skeleton& sk, const std::string& name);
  double total_mass() const;
  // Height from the lowest to the highest point of the bodies in the rest pose (metres).
  double rest_height() const;
  // Height of the root above the lowest body point in the rest pose: standing root height.
  double rest_root_height() const;
  // Throws Error unless there is one body and one gain per joint with positive masses.
  void validate() const;
};

struct MjcfOptions {
  double timestep = 1.0 / 600.0;   // physics step (s)
  bool floor = true;
  double armature = 0.01;          // added rotor inertia per joint DoF: steadies light links
  double friction = 0.9;
  // Extra MJCF inside <asset> and <worldbody> (terrain, projectiles): added as given.
  std::string extra_assets;
  std::string extra_worldbody;
};

// MJCF text of the character standing on a floor. Joints keep the skeleton's names; bodies are
// named like their joints; ball/hinge joint damping carries the PD kd (MuJoCo integrates it
// implicitly), the kp part is applied by the simulation (sim/world.hpp).
std::string build_mjcf(const CharacterModel& ch, const MjcfOptions& opts = {});

}  // namespace mimic
