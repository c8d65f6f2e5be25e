#pragma once
// Observation builders of a simulated character, selected by name in a config:
//   full_state       root height, root rotation in the heading frame, joint rotations (quaternion
//                    per spherical joint, angle per revolute), root linear and angular velocity in
//                    the heading frame, joint velocities
//   egocentric       seed 000's proprioception: velocimeter and gyro (root frame), uprightness
//                    (world up in the root frame), root -> end effectors and head (root frame)
//   links            seed 004 section 4.1: every link's position and quaternion over the last K
//                    control steps, in the heading frame of the latest one
//   link_velocities  every link's linear and angular velocity in the heading frame
//   phase            the reference clip's phase in [0, 1)
//   reference_root   the reference clip's root relative to the character's, in the heading frame
//                    (x ahead, y left, z up; m): where the clip is, so a tracking policy can hold
//                    its distance rather than learn a pace (a cyclic clip's root advances cycle
//                    by cycle)
//   height_map       terrain heights minus the root height on an n x n grid in the heading frame
//                    (seed 003's height-map input, after Peng et al. 2018): row i at
//                    x = ahead + (i - (n-1)/2) * spacing, column j at y = (j - (n-1)/2) * spacing,
//                    value [i * n + j]; default 11 x 11 at 0.2 m, centred 0.8 m ahead of the root
//                    (it sees 0.2 m behind to 1.8 m ahead, 1 m to each side)
#include <deque>
#include <string>
#include <vector>

#include "env/env.hpp"
#include "sim/terrain.hpp"
#include "sim/world.hpp"

namespace mimic {

// What an observation may look at.
struct ObservationContext {
  const World* world = nullptr;
  const std::deque<LinkFrames>* history = nullptr;  // latest last; at least one entry
  const Clip* reference = nullptr;                  // for "phase" and "reference_root"
  double time = 0.0;                                // episode time on the reference clip
  const Terrain* terrain = nullptr;                 // for "height_map"; none: flat ground at z = 0
};

struct ObservationConfig {
  std::vector<std::string> names{"full_state"};
  int link_history = 1;  // K for "links"
  int height_map_size = 11;          // n: points per side of the "height_map" grid
  double height_map_spacing = 0.2;   // metres between grid points
  double height_map_ahead = 0.8;     // grid centre ahead of the root along its heading (m)
};

class ObservationBuilder {
 public:
  // Throws Error naming an unknown observation, or "phase" or "reference_root" without a
  // reference clip.
  ObservationBuilder(const World& world, const ObservationConfig& cfg, bool has_reference);
  int size() const { return size_; }
  const std::vector<ObservationSlice>& layout() const { return layout_; }
  int link_history() const { return cfg_.link_history; }
  void build(const ObservationContext& ctx, Eigen::VectorXd& out) const;
  // World (x, y) of "height_map" grid point (i, j) for a heading frame.
  Vec3 height_map_point(const HeadingFrame& heading, int i, int j) const;

 private:
  int part_size(const std::string& name) const;
  ObservationConfig cfg_;
  Skeleton skeleton_;
  std::vector<int> ego_points_;  // joints whose root-relative vectors "egocentric" reports
  std::vector<int> dof_, body_;  // MuJoCo velocity address and body id per joint (-1: none)
  std::vector<ObservationSlice> layout_;
  int size_ = 0;
};

}  // namespace mimic
