#pragma once
// Motion reconstruction from keypoints (seed 003 §5): one trajectory of the character's poses
// that agrees with the 2D keypoints, stays near the per-frame 3D estimate where that agrees with
// the 2D, and moves smoothly:
//   w2D Σ_t Σ_j c_tj ‖x̂_tj − Π F_j(q_t)‖₁ + w3D Σ_t w_t Σ_k dist(q̂_tk, q_tk) + wsm Σ_t Σ_j ‖Δ F_j(q_t)‖²
// (Δ: seed 003's first difference between frames, or by default the second; see Smoothness)
// with w_t = exp(−δ_t), δ_t = Σ_j c_tj ‖x̂_tj − Π F_j(q̂_t)‖₂, Π a weak-perspective camera (each
// frame's joints share its pelvis's depth), 2D in units of half the image's height. The raw
// estimate q̂_t is each frame fitted alone: its joint rotations to the estimator's 3D keypoints,
// then its pelvis's place to the 2D ones. Solved with Ceres (docs/video.md).
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "motion/clip.hpp"
#include "video/keypoints.hpp"

namespace mimic {

// Which joint (or site) of the character each keypoint is: pairs keypoint name -> joint or site
// name. Empty: every keypoint named like a joint or site of the character is that one.
struct KeypointMap {
  std::vector<std::pair<std::string, std::string>> pairs;
  std::string source;  // the file, for messages
};
// A YAML file `keypoints: {nose: head, left_hip: left_hip, ...}`; ParseError naming the line.
KeypointMap load_keypoint_map(const std::filesystem::path& path);

// What the smoothness term penalises: joint positions' change between frames (seed 003's
// velocity) or its change (acceleration).
enum class Smoothness { Velocity, Acceleration };

// The defaults: seed 003's w2D and w3D; the smoothness term on accelerations, wsm 1000. On the
// benchmark with a known answer (docs/video.md), seed 003's velocity term at its wsm 25 barely
// moves the raw estimate (walk: MPJPE 4.88 -> 4.86 cm, jitter 382 -> 88 m/s²), and at weights
// that remove the jitter it slows the motion down (the run: 6.0 -> 10.4 cm at wsm 1000, w3D 10);
// accelerations cost nothing for steady motion.
struct ReconstructionOptions {
  double w2d = 10.0, w3d = 100.0, wsm = 1000.0;
  Smoothness smoothness = Smoothness::Acceleration;
  double fov_deg = 0.0;       // 0: the track's, else kDefaultFovDeg
  int min_keypoints = 6;      // a frame with fewer seen keypoints (or no 3D estimate) cannot be fitted
  int max_bridge = 5;         // inner runs of unfit frames up to this long are bridged by the smoothness term alone
  int min_frames = 10;        // fewer fitted frames than this: Error (too short)
  int max_iterations = 200;
  bool verbose = false;       // Ceres's per-iteration lines
};

// The loss terms unweighted, as in the formula above (2D in half-heights, angles in radians).
struct ReconstructionTerms {
  double l2d = 0, l3d = 0, lsm = 0;
};

struct ReconstructionReport {
  int first_frame = 0;                // the track's frame that became the clip's frame 0
  std::vector<int> unfit;             // track frames that could not be fitted (too few keypoints)
  std::vector<int> bridged;           // of those, the ones inside the clip, filled by the smoothness term
  std::vector<int> cut;               // of those, the ones left out (at the ends, or in gaps too long)
  std::vector<std::string> unused_keypoints;  // names with no joint or site of the character
  ReconstructionTerms raw, reconstructed;
  double mean_weight_3d = 0;          // mean of w_t over the fitted frames
  bool ground_fitted = false;         // false: the camera was taken as level (the feet never spread enough)
  double camera_pitch_deg = 0;        // the camera's view against the floor found (below it: negative)
  int raw_iterations = 0;             // the raw estimate's, over all frames
  double raw_seconds = 0;             // the raw estimate's part of `seconds`
  int iterations = 0;
  double seconds = 0;
};

struct Reconstruction {
  Clip raw;            // the per-frame estimate, in the same world as `reconstructed`
  Clip reconstructed;
  ReconstructionReport report;
};

// Throws Error naming the track when: fewer than 4 keypoints name joints of the character; the
// track has no 3D estimate; the longest stretch of fitted frames is shorter than min_frames.
Reconstruction reconstruct_motion(const KeypointTrack& track, const Skeleton& character, const KeypointMap& map,
                                  const ReconstructionOptions& opts = {});

// One frame's pose alone, as the raw estimate fits it (its joint rotations to the frame's 3D
// keypoints), for motion completion from a still (seed 003 §8): the camera taken as level (one
// frame shows no floor), the pelvis above the origin, the lowest point on the floor. Throws Error
// naming the track and the frame when it has no such frame, no 3D estimate or too few keypoints
// seen (opts.min_keypoints; the other options but fov_deg are not used).
Pose estimate_frame_pose(const KeypointTrack& track, int frame, const Skeleton& character, const KeypointMap& map,
                         const ReconstructionOptions& opts = {});

}  // namespace mimic
