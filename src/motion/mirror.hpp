#pragma once
// Left/right mirroring about the character's sagittal plane (mimic's X-Z plane, Y -> -Y).
#include <vector>

#include "motion/clip.hpp"

namespace mimic {

// For each joint, the index of its mirror twin (itself for centre joints), found by names:
// left/right, Left/Right, LEFT/RIGHT anywhere in the name, or a leading l/r, L/R (lfemur/rfemur,
// LHipJoint/RHipJoint), or a trailing _l/_r, .L/.R. Pairs must have the same parent's twin.
std::vector<int> mirror_map(const Skeleton& sk);

// The mirrored clip: twins swap motions, every rotation and position is reflected. Exact for
// skeletons whose twins are mirror images; mirroring twice gives the original clip back always.
Clip mirror(const Clip& clip);
Clip mirror(const Clip& clip, const std::vector<int>& twin);

}  // namespace mimic
