#pragma once
// Kinematic playback of a clip on a simulated character, rendered to MP4/GIF: the camera follows
// the character; an optional translucent ghost replays the clip beside it.
#include <filesystem>

#include "render/offscreen.hpp"
#include "sim/character_model.hpp"

namespace mimic {

struct ClipVideoOptions {
  int width = 640, height = 480;
  double fps = 30.0;
  double seconds = 0.0;                // 0: the clip's duration (wrap clips: one cycle)
  bool ghost = false;
  Vec3 ghost_offset = Vec3(0, 1.0, 0);  // ghost position relative to the character
  // lookat is added to the root's ground point raised to 55% of the character's height; a
  // distance of 0 frames the character (2.2 times its height).
  CameraSpec camera{Vec3::Zero(), 0.0, 90.0, -12.0};
  // A camera that does not move (fixed_clip_camera) instead of one following the root: what the
  // video shows of the character's travel is then its own (a pose model sees it cross the picture).
  bool fixed_camera = false;
};

// The fixed camera over `seconds` of `clip` at `fps`: looking at the middle of the box around its
// root's ground path, raised to 55% of the character's `height` (plus base.lookat), from the
// distance that keeps the whole box and 0.5 m beyond it in the picture's width (MuJoCo's
// 45-degree vertical field of view at this `aspect`, width / height), never nearer than the
// following camera's 2.2 heights; base's azimuth and elevation.
CameraSpec fixed_clip_camera(const Clip& clip, double seconds, double fps, double height, double aspect, const CameraSpec& base);

// Returns the number of frames written. Throws Error if no GL context or ffmpeg is available.
int render_clip_video(const CharacterModel& ch, const Clip& clip, const std::filesystem::path& out, const ClipVideoOptions& opts = {});

}  // namespace mimic
