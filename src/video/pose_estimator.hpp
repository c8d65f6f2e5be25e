#pragma once
// A real pose model on a video: BlazePose (MediaPipe's GHUM model, 33 landmarks with 3D world
// coordinates) run by mimic's Node sidecar (tools/pose, installed by scripts/setup.sh), frames
// decoded by ffmpeg. What `mimic video keypoints` runs (docs/video.md).
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "video/keypoints.hpp"

namespace mimic {

// BlazePose's 33 landmark names (MediaPipe's), person's left and right: the keypoint names of a
// track it makes. Twelve of them (shoulders, elbows, wrists, hips, knees, ankles) are named like
// the joints of DeepMimic's humanoid and mimic's built-in one.
const std::vector<std::string>& blazepose_names();

struct PoseEstimatorOptions {
  std::string variant = "full";     // BlazePose's lite, full or heavy model
  std::filesystem::path sidecar;    // the sidecar's folder; empty: $MIMIC_POSE_DIR, else tools/pose in the source tree
  double fov_deg = 0.0;             // the camera's vertical field of view where known (kept in the file)
  std::function<void(int frames)> progress;  // called every 30 frames
};

// Throws Error naming the video when ffmpeg cannot read it or it holds no person in any frame,
// and naming the sidecar when it is not installed or fails (with its message).
KeypointTrack estimate_keypoints(const std::filesystem::path& video, const PoseEstimatorOptions& opts = {});

}  // namespace mimic
