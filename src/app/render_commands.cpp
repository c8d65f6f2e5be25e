// mimic render CLIP -o out.mp4; mimic character build CHARACTER -o model.xml
#include <spdlog/spdlog.h>

#include <algorithm>

#include "app/commands.hpp"
#include "app/policy_video.hpp"
#include "core/error.hpp"
#include "core/file_io.hpp"
#include "env/planar_walker.hpp"
#include "env/reacher_arm.hpp"
#include "motion/asf_amc.hpp"
#include "motion/deepmimic.hpp"
#include "render/clip_video.hpp"

namespace mimic::app {

namespace {

// The DeepMimic character of the shared data whose skeleton the clip is on (the same joints,
// parents and offsets): where `mimic reconstruct`, `mimic imitate` and retargeting put clips.
// Empty when none is.
std::filesystem::path character_with_skeleton(const Skeleton& sk) {
  const std::filesystem::path dir = shared_data_dir() / "deepmimic" / "characters";
  std::error_code ec;
  if (shared_data_dir().empty() || !std::filesystem::is_directory(dir, ec)) return {};
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec))
    if (e.path().extension() == ".txt" && e.path().stem().string().find("_ctrl") == std::string::npos) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (const auto& f : files) {
    Skeleton c;
    try {
      c = load_deepmimic_character(f).skeleton;
    } catch (const Error&) {
      continue;  // not a character file
    }
    bool same = c.joints.size() == sk.joints.size();
    for (std::size_t j = 0; same && j < c.joints.size(); ++j)
      same = c.joints[j].name == sk.joints[j].name && c.joints[j].parent == sk.joints[j].parent && (c.joints[j].offset - sk.joints[j].offset).norm() < 1e-6;
    if (same) return f;
  }
  return {};
}

}  // namespace

CharacterModel character_for(const Clip& clip, const std::filesystem::path& input, const LoadOptions& load) {
  std::filesystem::path ch_path = load.character;
  if (ch_path.empty() && input.extension() == ".txt") ch_path = guess_deepmimic_character(input);
  if (ch_path.empty() && input.extension() == ".mclip") ch_path = character_with_skeleton(clip.skeleton);
  if (ch_path.empty()) return CharacterModel::from_skeleton(clip.skeleton, clip.name);
  std::filesystem::path ctrl = ch_path.parent_path() / (ch_path.stem().string() + "_ctrl.txt");
  CharacterModel ch = CharacterModel::from_deepmimic(ch_path, std::filesystem::exists(ctrl) ? ctrl : std::filesystem::path{});
  for (int j = 0; j < ch.skeleton.num_joints(); ++j) {
    if (j >= clip.skeleton.num_joints() || clip.skeleton.joints[static_cast<std::size_t>(j)].name != ch.skeleton.joints[static_cast<std::size_t>(j)].name)
      throw Error(input.string() + ": the clip's skeleton does not fit the character " + ch_path.string() + " (joint " +
                  std::to_string(j) + " '" + ch.skeleton.joints[static_cast<std::size_t>(j)].name + "' differs or is missing)");
  }
  if (clip.skeleton.num_joints() != ch.skeleton.num_joints())
    throw Error(input.string() + ": the clip has more joints than the character " + ch_path.string());
  return ch;
}

void add_render_commands(CLI::App& app) {
  struct Args {
    std::filesystem::path input, output, controller;
    double mass = 70.0;
    std::string builtin;
    std::vector<int> contexts;
    double context_seconds = 5.0;
    std::vector<std::string> settings;
    LoadOptions load;
    ClipVideoOptions video;
  };
  auto args = std::make_shared<Args>();
  CLI::App* render = app.add_subcommand("render", "video (.mp4 or .gif) of a clip played on a simulated character, or of a trained policy");
  render->add_option("input", args->input, "motion file, or a training run directory (its policy acting)")->required()->check(CLI::ExistingPath);
  render->add_option("-o,--output", args->output, "output .mp4 or .gif")->required();
  render->add_flag("--ghost", args->video.ghost, "also draw the clip as a translucent ghost beside the character (a run: its reference, over it)");
  render->add_flag("--fixed-camera", args->video.fixed_camera,
                   "a clip: a camera that does not move, framing the root's whole path (default: one following the root), so that "
                   "the video shows the character's travel, as a pose model needs to recover it");
  render->add_option("--seconds", args->video.seconds, "length (default: the clip's duration)");
  render->add_option("--width", args->video.width, "pixels")->capture_default_str()->check(CLI::Range(16, 1280));
  render->add_option("--height", args->video.height, "pixels")->capture_default_str()->check(CLI::Range(16, 720));
  render->add_option("--contexts", args->contexts, "a run over behaviour contexts: hold these in turn, e.g. 0,1 (default: drawn as in training)")
      ->delimiter(',')
      ->check(CLI::NonNegativeNumber);
  render->add_option("--context-seconds", args->context_seconds, "how long each of --contexts is held")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  render->add_option("--set", args->settings,
                     "a run's environment for this video: env.KEY=VALUE over its config (e.g. \"env.terrain={kind: walls}\"); repeatable");
  add_load_options(*render, args->load);
  render->callback([args] {
    for (const std::string& setting : args->settings)
      if (setting.rfind("env.", 0) != 0) throw Error("--set " + setting + ": render overrides environment keys only (env.KEY=VALUE)");
    if (std::filesystem::is_directory(args->input)) {
      if (args->video.fixed_camera) throw Error(args->input.string() + ": --fixed-camera is for a clip; a policy's video follows its character");
      PolicyVideoOptions o;
      o.env_settings = args->settings;
      o.width = args->video.width, o.height = args->video.height, o.ghost = args->video.ghost;
      o.contexts = args->contexts, o.context_seconds = args->context_seconds;
      if (args->video.seconds > 0) o.seconds = args->video.seconds;
      const PolicyVideoStats s = render_policy_video(args->input, args->output, o);
      spdlog::info("wrote {} ({} frames at {:.1f} fps); {} episode(s) ended", args->output.string(), s.frames, s.fps, s.episodes.size());
      for (const auto& [ret, why] : s.episodes) spdlog::info("  episode return {:.2f}, ended by {}", ret, to_string(why));
      return;
    }
    if (!args->contexts.empty()) throw Error(args->input.string() + ": --contexts is for a training run's policy, not a clip");
    if (!args->settings.empty()) throw Error(args->input.string() + ": --set is for a training run's environment, not a clip");
    const Clip clip = load_motion(args->input, args->load);
    const CharacterModel ch = character_for(clip, args->input, args->load);
    const int frames = render_clip_video(ch, clip, args->output, args->video);
    spdlog::info("wrote {} ({} frames at {} fps, character '{}')", args->output.string(), frames, args->video.fps, ch.name);
  });

  CLI::App* character = app.add_subcommand("character", "simulated characters");
  character->require_subcommand(1);
  CLI::App* build = character->add_subcommand("build", "write the MuJoCo model (MJCF) of a character or of a clip's skeleton");
  auto* source = build->add_option("source", args->input, "DeepMimic character file, an ASF skeleton, or any motion file (its skeleton)")->check(CLI::ExistingFile);
  build->add_option("--builtin", args->builtin, "a validation body instead: walker, arm2 or arm3 (seeds 000/002)")
      ->check(CLI::IsMember({"walker", "arm2", "arm3"}))->excludes(source);
  build->add_option("--ctrl", args->controller, "DeepMimic PD-controller file (gains)");
  build->add_option("--mass", args->mass, "body mass (kg) of a body generated from a skeleton")->capture_default_str();
  build->add_option("-o,--output", args->output, "output .xml")->required();
  build->callback([args] {
    if (!args->builtin.empty()) {
      const std::string xml = args->builtin == "walker" ? planar_walker_mjcf()
                              : reacher_arm_mjcf(args->builtin == "arm2" ? ReacherConfig::two_link() : ReacherConfig::three_link());
      write_file_atomic(args->output, xml);
      spdlog::info("wrote {} ({})", args->output.string(), args->builtin);
      return;
    }
    if (args->input.empty()) throw Error("character build: give a source file or --builtin");
    CharacterModel ch;
    const bool is_character = args->input.extension() == ".txt" && read_text_file(args->input).find("\"Skeleton\"") != std::string::npos;
    if (is_character) ch = CharacterModel::from_deepmimic(args->input, args->controller);
    else if (args->input.extension() == ".asf") ch = CharacterModel::from_skeleton(load_asf(args->input).skeleton, args->input.stem().string(), args->mass);
    else ch = CharacterModel::from_skeleton(load_motion(args->input, args->load).skeleton, args->input.stem().string(), args->mass);
    write_file_atomic(args->output, build_mjcf(ch));
    spdlog::info("wrote {}: {} bodies, {:.2f} kg, {:.3f} m tall at rest", args->output.string(), ch.bodies.size(), ch.total_mass(), ch.rest_height());
  });
  add_load_options(*build, args->load);
}

}  // namespace mimic::app
