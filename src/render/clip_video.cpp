#include "render/clip_video.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "render/video_writer.hpp"
#include "sim/world.hpp"

namespace mimic {

CameraSpec fixed_clip_camera(const Clip& clip, double seconds, double fps, double height, double aspect, const CameraSpec& base) {
  Eigen::Vector2d lo = clip.sample(0).root_pos.head<2>(), hi = lo;
  const int frames = std::max(1, static_cast<int>(std::lround(seconds * fps)));
  for (int f = 1; f <= frames; ++f) {
    const Eigen::Vector2d p = clip.sample(static_cast<double>(f) / fps).root_pos.head<2>();
    lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  }
  CameraSpec cam = base;
  const Eigen::Vector2d mid = (lo + hi) / 2;
  cam.lookat = Vec3(mid.x(), mid.y(), 0.55 * height) + base.lookat;
  constexpr double kHalfFovy = 22.5 * kPi / 180;  // MuJoCo's default fovy, 45 degrees
  const double half_width = std::atan(std::tan(kHalfFovy) * aspect);
  cam.distance = std::max(2.2 * height, ((hi - lo).norm() / 2 + 0.5) / std::tan(half_width));
  return cam;
}

int render_clip_video(const CharacterModel& ch, const Clip& clip, const std::filesystem::path& out, const ClipVideoOptions& opts) {
  if (clip.skeleton.num_joints() != ch.skeleton.num_joints())
    throw Error("clip '" + clip.name + "' has " + std::to_string(clip.skeleton.num_joints()) + " joints, character '" + ch.name +
                "' has " + std::to_string(ch.skeleton.num_joints()));
  World world(ch);
  World ghost(ch);
  OffscreenRenderer renderer(world.model(), opts.width, opts.height);
  VideoWriter video(out, opts.width, opts.height, opts.fps);
  const double seconds = opts.seconds > 0 ? opts.seconds : clip.duration();
  const int frames = std::max(1, static_cast<int>(std::lround(seconds * opts.fps)) + (opts.seconds > 0 ? 0 : 1));
  std::vector<std::uint8_t> rgb;
  const double height = ch.rest_height();
  Vec3 smoothed = clip.frames.front().root_pos;
  const CameraSpec fixed = fixed_clip_camera(clip, seconds, opts.fps, height, static_cast<double>(opts.width) / opts.height, opts.camera);
  for (int f = 0; f < frames; ++f) {
    const Pose pose = clip.sample(static_cast<double>(f) / opts.fps);
    world.set_state(pose);
    if (opts.ghost) {
      Pose g = pose;
      g.root_pos += HeadingFrame::of(pose).yaw * opts.ghost_offset;
      ghost.set_state(g);
    }
    // Follow the root on the ground, smoothed so the picture does not shake with the gait.
    smoothed = f == 0 ? pose.root_pos : 0.9 * smoothed + 0.1 * pose.root_pos;
    CameraSpec cam = opts.camera;
    cam.lookat = Vec3(smoothed.x(), smoothed.y(), 0.55 * height) + opts.camera.lookat;
    if (cam.distance <= 0) cam.distance = 2.2 * height;
    if (opts.ghost) cam.lookat += 0.5 * (HeadingFrame::of(pose).yaw * opts.ghost_offset);
    if (opts.fixed_camera) cam = fixed;
    renderer.render(world.data(), cam, rgb, opts.ghost ? ghost.data() : nullptr);
    video.write(rgb);
  }
  video.close();
  return frames;
}

}  // namespace mimic
