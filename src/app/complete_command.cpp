// `mimic complete`: motion completion from a still (seed 003 §8, docs/video.md): the pose in an
// image (or a keypoint file's frame), the skills' nearest clip frame, and the character started
// from the pose and driven on by that frame's skill.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <memory>

#include "app/commands.hpp"
#include "control/completion.hpp"
#include "core/error.hpp"
#include "core/file_io.hpp"
#include "render/offscreen.hpp"
#include "render/video_writer.hpp"
#include "video/pose_estimator.hpp"
#include "video/reconstruct.hpp"

namespace mimic::app {

namespace {

struct CompleteArgs {
  std::filesystem::path input, output, json, map;
  std::vector<std::filesystem::path> skills;
  int frame = 0;
  double seconds = 4.0;
  std::uint64_t seed = 1;
  PoseEstimatorOptions pose;
  int width = 640, height = 480;
  std::string start = "frame";
};

bool is_keypoint_file(const std::filesystem::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".json";
}

void run(const CompleteArgs& a) {
  std::vector<std::shared_ptr<const Skill>> skills;
  for (const auto& dir : a.skills) {
    spdlog::info("loading {}", dir.string());
    skills.push_back(Skill::load(dir));
    for (std::size_t i = 0; i + 1 < skills.size(); ++i)
      if (skills[i]->name() == skills.back()->name())
        throw Error("complete: two skills are named '" + skills.back()->name() + "' (a skill is named by its directory, a run's RUN/model by its run; give each model once)");
  }
  const MotionCompletion completion(skills);

  KeypointTrack track;
  if (is_keypoint_file(a.input)) {
    track = load_keypoints(a.input);
  } else {
    if (a.frame != 0) throw Error("complete: --frame picks a frame of a keypoint file; an image has one");
    spdlog::info("{}: estimating the pose (BlazePose {})", a.input.string(), a.pose.variant);
    track = estimate_keypoints(a.input, a.pose);
  }
  ReconstructionOptions opts;
  opts.fov_deg = a.pose.fov_deg;
  const KeypointMap map = a.map.empty() ? KeypointMap{} : load_keypoint_map(a.map);
  const Pose pose = estimate_frame_pose(track, a.frame, completion.skeleton(), map, opts);
  const std::vector<CompletionMatch> matches = completion.match(pose);

  fmt::print("nearest frame of each skill (mean joint distance from the pose):\n");
  for (const CompletionMatch& m : matches)
    fmt::print("  {:<32} {:>6.3f} m  {} frame {} ({:.2f} s)\n", skills[m.skill]->name(), m.distance, m.clip, m.frame, m.time);
  const CompletionMatch& best = matches.front();
  const std::string chosen = skills[best.skill]->name();
  fmt::print("completing with {}, from {}\n", chosen, a.start == "pose" ? "the pose seen, with the frame's velocities" : "the frame");

  // The character started from the pose and driven by the chosen skill.
  Controller controller(skills, a.seed);
  completion.start(controller, pose, best, a.start == "pose" ? MotionCompletion::StartAt::Pose : MotionCompletion::StartAt::Frame);
  const double dt = controller.control_dt();
  const long long steps = std::llround(a.seconds / dt);
  std::unique_ptr<OffscreenRenderer> renderer;
  std::unique_ptr<VideoWriter> video;
  if (!a.output.empty()) {
    renderer = std::make_unique<OffscreenRenderer>(controller.physics_model(), a.width, a.height);
    video = std::make_unique<VideoWriter>(a.output, a.width, a.height, 1.0 / dt);
  }
  CameraFollow follow;
  std::vector<std::uint8_t> rgb;
  auto film = [&] {
    if (!video) return;
    CameraSpec cam{follow.update(Vec3(controller.root_position())), 4.0, 90.0, -12.0};
    cam.lookat.z() = 0.9;
    renderer->render(controller.physics_data(), cam, rgb);
    video->write(rgb);
  };
  film();
  double ended = -1;
  std::string ending;
  for (long long i = 0; i < steps; ++i) {
    const StepInfo info = controller.step();
    film();
    if (info.episode_over) {
      ended = controller.time(), ending = info.ending;
      break;
    }
  }
  const bool fell = ending == "fall" || ending == "drift";
  if (ended < 0) fmt::print("simulated {:.1f} s: the character stayed up\n", controller.time());
  else fmt::print("simulated {:.1f} s: the episode ended ({}) at {:.2f} s\n", controller.time(), ending, ended);
  if (video) {
    video->close();
    spdlog::info("wrote {} ({} frames)", a.output.string(), video->frames());
  }
  if (!a.json.empty()) {
    std::string j = "{\n  \"input\": " + json_string(a.input.string()) + ",\n  \"frame\": " + std::to_string(a.frame) + ",\n  \"matches\": [";
    for (std::size_t i = 0; i < matches.size(); ++i) {
      const CompletionMatch& m = matches[i];
      j += std::string(i ? "," : "") + "\n    {\"skill\": " + json_string(skills[m.skill]->name()) + ", \"clip\": " + json_string(m.clip) +
           ", \"frame\": " + std::to_string(m.frame) + ", \"time\": " + json_number(m.time) + ", \"distance_m\": " + json_number(m.distance) + "}";
    }
    j += "\n  ],\n  \"skill\": " + json_string(chosen) + ",\n  \"start\": " + json_string(a.start) + ",\n  \"seconds\": " + json_number(controller.time()) +
         ",\n  \"ending\": " + json_string(ending) + ",\n  \"fell\": " + (fell ? "true" : "false") + "\n}\n";
    write_file_atomic(a.json, j);
  }
}

}  // namespace

void add_complete_command(CLI::App& app) {
  auto a = std::make_shared<CompleteArgs>();
  CLI::App* cmd = app.add_subcommand("complete", "motion completion from a still (seed 003 §8): the pose in an image, the skills' nearest "
                                                 "clip frame, and the character driven on from the pose by that skill");
  cmd->add_option("input", a->input, "an image (anything ffmpeg reads; the pose model estimates the pose) or a keypoint file (.json, with 3D keypoints)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--skills", a->skills, "model directories of one character whose episodes start from clips (mimic imitate's, models/)")
      ->required()
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--frame", a->frame, "the keypoint file's frame (from 0)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--seconds", a->seconds, "how long to simulate")->capture_default_str()->check(CLI::NonNegativeNumber);
  cmd->add_option("-o,--output", a->output, "a video of the simulation (.mp4)");
  cmd->add_option("--json", a->json, "the matches and the outcome as JSON");
  cmd->add_option("--map", a->map, "keypoint map (YAML) where keypoint names are not the character's joints (docs/video.md)")->check(CLI::ExistingFile);
  cmd->add_option("--fov", a->pose.fov_deg, "the camera's vertical field of view, degrees (default: the file's, else 55)")->check(CLI::PositiveNumber);
  cmd->add_option("--variant", a->pose.variant, "BlazePose model for an image: lite, full or heavy")
      ->capture_default_str()
      ->check(CLI::IsMember({"lite", "full", "heavy"}));
  cmd->add_option("--start", a->start, "where the character starts: the matched frame, or the pose seen with the frame's velocities (seed 003)")
      ->capture_default_str()
      ->check(CLI::IsMember({"frame", "pose"}));
  cmd->add_option("--seed", a->seed, "the controller's seed")->capture_default_str();
  cmd->callback([a] { run(*a); });
}

}  // namespace mimic::app
