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
  // A body generated for any skeleton (BVH, ASF, .mclip), as seed 000 built its CMU humanoid
  // from segment lengths: per joint a capsule along its bone (towards the farthest child or its
  // site; a sphere where there is none; a foot without a toe joint stands on a sole box under its
  // site) with a radius by body part, masses in proportion to
  // volume summing to `total_mass`, and servo gains and torque limits by body part (strong legs
  // and torso, weak hands and toes), scaled with the mass.
  static CharacterModel from_skeleton(const Skeleton& sk, const std::string& name, double total_mass = 70.0);
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
  // MuJoCo 2.2's nconmax / njmax. Larger buffers cost time every step (1,000 / 4,000 made the
  // humanoid 18% slower on flat ground), so only terrain and projectiles ask for more.
  int max_contacts = 200;
  int max_constraints = 1000;
  // Extra MJCF inside <asset> and <worldbody> (terrain, projectiles): added as given.
  std::string extra_assets;
  std::string extra_worldbody;
  // The size of the scene a renderer frames (MJCF <statistic extent>, metres; 0: MuJoCo's own,
  // from the bodies' positions). Visual only. Bodies parked far away (projectiles) would make
  // MuJoCo's own so large that its near clipping plane cuts the character out of the picture.
  double visual_extent = 0;
};

// MJCF text of the character standing on a floor. Joints keep the skeleton's names; bodies are
// named like their joints; ball/hinge joint damping carries the PD kd (MuJoCo integrates it
// implicitly), the kp part is applied by the simulation (sim/world.hpp).
std::string build_mjcf(const CharacterModel& ch, const MjcfOptions& opts = {});

}  // namespace mimic
