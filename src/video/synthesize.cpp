#include "video/synthesize.hpp"

#include <cmath>
#include <random>

#include "core/error.hpp"
#include "motion/kinematics.hpp"

namespace mimic {

SynthesisResult synthesize_keypoints(const Clip& clip, const SynthesisOptions& o) {
  clip.validate();
  if (!(o.fps > 0) || !(o.distance > 0) || o.width <= 0 || o.height_px <= 0 || !(o.fov_deg > 0 && o.fov_deg < 180))
    throw Error("keypoint synthesis: the rate, distance, image size and field of view must be positive (field of view below 180)");
  if (o.pixel_noise < 0 || o.world_noise < 0 || !(o.dropout >= 0 && o.dropout < 1) || !(o.min_confidence > 0 && o.min_confidence <= 1))
    throw Error("keypoint synthesis: noise must be non-negative, dropout in [0, 1), the lowest confidence in (0, 1]");
  const int n = static_cast<int>(std::floor(clip.duration() * o.fps + 1e-9)) + 1;
  std::vector<LinkFrames> frames(static_cast<std::size_t>(n));
  Vec3 centre = Vec3::Zero();
  for (int i = 0; i < n; ++i) {
    forward_kinematics(clip.skeleton, clip.sample(i / o.fps), frames[static_cast<std::size_t>(i)]);
    centre += frames[static_cast<std::size_t>(i)].joint_pos[0] / n;
  }
  const double heading = heading_angle(clip.frames.front().rot[0]) + deg_to_rad(o.azimuth_deg);
  const Vec3 eye(centre.x() + o.distance * std::cos(heading), centre.y() + o.distance * std::sin(heading), o.height);
  SynthesisResult out;
  out.camera = PinholeCamera::looking_at(eye, centre, o.fov_deg, o.width, o.height_px);
  KeypointTrack& t = out.track;
  t.source = clip.name + " (synthesised)";
  t.fps = o.fps;
  t.width = o.width, t.height = o.height_px;
  t.fov_deg = o.fov_deg;
  for (const Joint& j : clip.skeleton.joints) t.names.push_back(j.name);
  std::mt19937_64 rng(o.seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (int i = 0; i < n; ++i) {
    const LinkFrames& lf = frames[static_cast<std::size_t>(i)];
    KeypointFrame f;
    const Vec3 pelvis = out.camera.to_camera(lf.joint_pos[0]);
    for (std::size_t k = 0; k < lf.joint_pos.size(); ++k) {
      const Vec3 p = out.camera.to_camera(lf.joint_pos[k]);
      if (p.z() < 1.0) throw Error(clip.name + ": frame " + std::to_string(i) + " passes within 1 m of the camera; place it further (--distance)");
      const double c = o.min_confidence + (1.0 - o.min_confidence) * uniform(rng);
      const double sigma = o.pixel_noise / c;
      const Vec2 px = out.camera.project(lf.joint_pos[k]) + sigma * Vec2(gauss(rng), gauss(rng));
      const bool dropped = uniform(rng) < o.dropout;
      f.pixel.push_back(dropped ? Vec2::Zero() : px);
      f.confidence.push_back(dropped ? 0.0 : c);
      f.world.push_back(p - pelvis + o.world_noise * Vec3(gauss(rng), gauss(rng), gauss(rng)));
    }
    t.frames.push_back(std::move(f));
  }
  t.validate();
  return out;
}

}  // namespace mimic
