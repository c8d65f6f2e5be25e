// `mimic video`: keypoints of a person, from a video or, for the benchmark with a known answer,
// from a clip seen through a known camera (docs/video.md).
#include <spdlog/spdlog.h>

#include <algorithm>
#include <memory>

#include "app/commands.hpp"
#include "video/pose_estimator.hpp"
#include "video/synthesize.hpp"

namespace mimic::app {

namespace {

struct KeypointArgs {
  std::filesystem::path input, output;
  PoseEstimatorOptions pose;
};

struct SynthArgs {
  std::filesystem::path input, output;
  LoadOptions load;
  SynthesisOptions synth;
};

}  // namespace

void add_video_commands(CLI::App& app) {
  CLI::App* video = app.add_subcommand("video", "keypoints of a person in a video, the first step of learning a skill from one (docs/video.md)");
  video->require_subcommand(1);

  auto kargs = std::make_shared<KeypointArgs>();
  CLI::App* keypoints = video->add_subcommand("keypoints", "a person's keypoints in every frame of a video: BlazePose's 33 landmarks, "
                                                           "pixels with a confidence and 3D (the pose model installed by scripts/setup.sh)");
  keypoints->add_option("video", kargs->input, "video file (anything ffmpeg reads)")->required()->check(CLI::ExistingFile);
  keypoints->add_option("-o,--output", kargs->output, "keypoint file (.json)")->required();
  keypoints->add_option("--variant", kargs->pose.variant, "BlazePose model: lite, full or heavy")
      ->capture_default_str()
      ->check(CLI::IsMember({"lite", "full", "heavy"}));
  keypoints->add_option("--fov", kargs->pose.fov_deg, "the camera's vertical field of view in degrees, where known (kept for mimic reconstruct)");
  keypoints->callback([kargs] {
    kargs->pose.progress = [](int frames) { spdlog::info("{} frames", frames); };
    const KeypointTrack t = estimate_keypoints(kargs->input, kargs->pose);
    save_keypoints(t, kargs->output);
    const auto seen = std::count_if(t.frames.begin(), t.frames.end(), [](const KeypointFrame& f) { return !f.empty(); });
    spdlog::info("wrote {}: a person in {} of {} frames ({}x{} pixels at {:.3g} fps)", kargs->output.string(), seen, t.num_frames(), t.width,
                 t.height, t.fps);
  });

  auto args = std::make_shared<SynthArgs>();
  CLI::App* synth = video->add_subcommand("synth", "keypoints a known camera sees of a clip, with a pose estimator's errors at stated levels: "
                                                   "the benchmark with a known answer for `mimic reconstruct --truth`");
  synth->add_option("clip", args->input, "motion file (the truth)")->required()->check(CLI::ExistingFile);
  synth->add_option("-o,--output", args->output, "keypoint file (.json)")->required();
  SynthesisOptions& s = args->synth;
  synth->add_option("--distance", s.distance, "camera's horizontal distance from the clip's centre, metres")->capture_default_str();
  synth->add_option("--azimuth", s.azimuth_deg, "camera's direction from the clip's centre, degrees from the clip's first heading")->capture_default_str();
  synth->add_option("--camera-height", s.height, "camera's height, metres")->capture_default_str();
  synth->add_option("--fov", s.fov_deg, "vertical field of view, degrees")->capture_default_str();
  synth->add_option("--fps", s.fps, "video frame rate")->capture_default_str();
  synth->add_option("--pixel-noise", s.pixel_noise, "2D error, pixels (std per coordinate at confidence 1; divided by the confidence)")->capture_default_str();
  synth->add_option("--min-confidence", s.min_confidence, "confidences are uniform between this and 1")->capture_default_str();
  synth->add_option("--dropout", s.dropout, "probability that a keypoint is not seen in a frame")->capture_default_str();
  synth->add_option("--world-noise", s.world_noise, "3D error, metres (std per coordinate, relative to the pelvis)")->capture_default_str();
  synth->add_option("--seed", s.seed, "random seed of the errors")->capture_default_str();
  add_load_options(*synth, args->load);
  synth->callback([args] {
    const SynthesisResult r = synthesize_keypoints(load_motion(args->input, args->load), args->synth);
    save_keypoints(r.track, args->output);
    spdlog::info("wrote {}: {} frames of {} keypoints at {} fps, {}x{} pixels, camera at ({:.2f}, {:.2f}, {:.2f})", args->output.string(),
                 r.track.num_frames(), r.track.names.size(), r.track.fps, r.track.width, r.track.height, r.camera.position.x(),
                 r.camera.position.y(), r.camera.position.z());
  });
}

}  // namespace mimic::app
