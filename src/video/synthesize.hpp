#pragma once
// Keypoints with a known answer: what a known camera sees of a clip, with the errors of a pose
// estimator added at stated levels. The ground-truth benchmark of `mimic reconstruct`
// (docs/video.md): the clip is the truth the reconstruction is measured against.
#include <cstdint>

#include "motion/clip.hpp"
#include "video/camera.hpp"
#include "video/keypoints.hpp"

namespace mimic {

struct SynthesisOptions {
  double distance = 6.0;      // metres from the clip's mean root position, horizontally
  double azimuth_deg = 60.0;  // the camera's direction from the clip's centre, about +Z from the clip's first heading
  double height = 1.2;        // the camera's height, metres (it looks at the clip's mean root)
  double fov_deg = kDefaultFovDeg;
  int width = 1280, height_px = 720;
  double fps = 30.0;          // the video's rate (the clip is sampled at it)
  // Estimator errors. 2D: Gaussian, `pixel_noise` pixels (std per coordinate) at confidence 1 and
  // pixel_noise / c at confidence c, c uniform in [min_confidence, 1]; a keypoint is dropped
  // (confidence 0) with probability `dropout`. 3D: Gaussian, `world_noise` metres per coordinate,
  // relative to the pelvis (BlazePose's world landmarks are about this far off).
  double pixel_noise = 3.0;
  double min_confidence = 0.5;
  double dropout = 0.05;
  double world_noise = 0.04;
  std::uint64_t seed = 1;
};

struct SynthesisResult {
  KeypointTrack track;  // one keypoint per joint of the clip's skeleton, named like the joint
  PinholeCamera camera;
};

// Throws Error when the camera would see the character from closer than 1 m (behind it or inside).
SynthesisResult synthesize_keypoints(const Clip& clip, const SynthesisOptions& opts);

}  // namespace mimic
