#pragma once
// How far an estimated motion is from the true one (the video benchmarks, docs/video.md), over
// the joints the two skeletons share by name:
// - MPJPE: mean joint position error relative to the root, after one rotation about the vertical
//   for the whole clip (the estimate's world faces where its camera looked);
// - PA-MPJPE: the same after the best similarity transform of each frame (Procrustes);
// - jitter: mean joint acceleration, ‖p(t+1) − 2p(t) + p(t−1)‖·fps², m/s².
#include "motion/clip.hpp"

namespace mimic {

struct PoseErrors {
  double mpjpe = 0, pa_mpjpe = 0;  // metres
  double jitter = 0;               // m/s², of the estimate
  int frames = 0, joints = 0;
};

// Frame i of `estimate` is compared with `truth` at time truth_start + i / estimate.fps. Throws
// Error when fewer than 4 joints share names or the estimate has fewer than 3 frames.
PoseErrors pose_errors(const Clip& estimate, const Clip& truth, double truth_start = 0.0);

// Mean joint acceleration of a clip (m/s²), every joint.
double jitter(const Clip& clip);

}  // namespace mimic
