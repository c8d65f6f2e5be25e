#pragma once
// What a pose estimator saw in a video, frame by frame: named 2D keypoints in pixels with a
// confidence each, and where the estimator gives them, 3D keypoints relative to the pelvis
// (metres, in the camera's axes: x right, y down, z away from the camera). The file format is
// mimic's keypoint JSON (docs/video.md); OpenPose's and COCO's files are read into the same.
#include <filesystem>
#include <string>
#include <vector>

#include "core/math.hpp"

namespace mimic {

using Vec2 = Eigen::Vector2d;

struct KeypointFrame {
  std::vector<Vec2> pixel;         // one per name; meaningless where confidence is 0
  std::vector<double> confidence;  // in [0, 1]; 0 = not seen
  std::vector<Vec3> world;         // one per name, or empty where the estimator gives no 3D
  // Whether the frame holds a person at all (a frame with none has empty vectors).
  bool empty() const { return pixel.empty(); }
};

struct KeypointTrack {
  std::string source;  // the file it came from, for messages
  double fps = 30.0;
  int width = 0, height = 0;  // image size, pixels
  double fov_deg = 0.0;       // vertical field of view where known; 0 = unknown
  std::vector<std::string> names;
  std::vector<KeypointFrame> frames;

  int num_frames() const { return static_cast<int>(frames.size()); }
  // Index of a keypoint by name, or -1.
  int find(const std::string& name) const;
  // Throws Error naming the source and the frame on the first inconsistency: sizes, confidences
  // outside [0, 1], non-finite values, an image size or rate that is not positive.
  void validate() const;
};

// mimic's keypoint JSON. Reading throws ParseError naming the file, line and key.
std::string write_keypoints(const KeypointTrack& track);
KeypointTrack parse_keypoints(std::string_view text, const std::string& source);
void save_keypoints(const KeypointTrack& track, const std::filesystem::path& path);  // atomic

// Any keypoint file mimic reads, by its content: mimic's JSON; OpenPose's per-frame JSON (a
// folder of *_keypoints.json, or one such file; BODY_25 or COCO-18 by the count); COCO's keypoint
// JSON (a dataset with "annotations" and "images", or a results list). Where the file holds no
// image size, `width`/`height` give it (Error when neither does); `fps` where it holds no rate.
struct KeypointReadOptions {
  int width = 0, height = 0;
  double fps = 30.0;
};
KeypointTrack load_keypoints(const std::filesystem::path& path, const KeypointReadOptions& opts = {});

}  // namespace mimic
