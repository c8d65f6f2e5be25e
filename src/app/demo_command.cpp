// mimic demo: the README's first command. Today: motion import, retargeting and pictures.
#include <spdlog/spdlog.h>

#include "app/commands.hpp"
#include "core/file_io.hpp"
#include "motion/builtin.hpp"
#include "motion/bvh.hpp"
#include "motion/deepmimic.hpp"
#include "motion/retarget.hpp"
#include "core/build_paths.hpp"
#include "render/clip_video.hpp"
#include "core/error.hpp"

namespace mimic::app {

namespace {

// Summary, .mclip, .svg picture and (unless disabled) an .mp4 of the clip on `ch`.
void show(const Clip& clip, const CharacterModel& ch, const std::filesystem::path& dir, double seconds, bool video,
          double azimuth, std::string& summary) {
  const std::string text = clip_summary(clip);
  fmt::print("{}\n", text);
  summary += text + "\n";
  write_motion(clip, dir / (clip.name + ".mclip"));
  write_motion(clip, dir / (clip.name + ".svg"));
  if (!video) return;
  ClipVideoOptions opts;
  opts.width = 480, opts.height = 360, opts.seconds = seconds, opts.ghost = true;
  opts.camera.azimuth = azimuth;
  try {
    const auto out = dir / (clip.name + ".mp4");
    const int frames = render_clip_video(ch, clip, out, opts);
    spdlog::info("rendered {} ({} frames; the translucent ghost replays the clip)", out.string(), frames);
  } catch (const Error& e) {
    spdlog::warn("no video: {}", e.what());
  }
}

}  // namespace

void add_demo_command(CLI::App& app) {
  auto out = std::make_shared<std::filesystem::path>("out/demo");
  auto video = std::make_shared<bool>(true);
  CLI::App* demo = app.add_subcommand("demo", "run mimic's showcase on built-in (and, if present, shared) motion");
  demo->add_option("-o,--output", *out, "output directory")->capture_default_str();
  demo->add_flag("!--no-video", *video, "skip the videos (pictures and clips only)");
  demo->callback([out, video] {
    std::string summary;
    // 1. Motion the project authors itself, on a simple body: always available.
    const Clip jack = builtin_jumping_jack();
    show(jack, CharacterModel::from_skeleton(jack.skeleton, "builtin_humanoid"), *out, 3.0, *video, 160.0, summary);
    // 2. Real capture: CMU walk retargeted onto the DeepMimic humanoid, when ../shared is here.
    const auto data = shared_data_dir();
    const auto bvh = data / "cmu-bvh/131_01.bvh", ch = data / "deepmimic/characters/humanoid3d.txt";
    const auto map = std::filesystem::path(kSourceDir) / "data/retarget/cmu_to_humanoid3d.yaml";
    if (!data.empty() && std::filesystem::exists(bvh) && std::filesystem::exists(ch) && std::filesystem::exists(map)) {
      const CharacterModel humanoid = CharacterModel::from_deepmimic(ch, data / "deepmimic/characters/humanoid3d_ctrl.txt");
      // 2. DeepMimic's walk on the simulated humanoid.
      show(load_deepmimic_motion(data / "deepmimic/motions/humanoid3d_walk.txt", humanoid.skeleton), humanoid, *out, 4.0, *video, 120.0, summary);
      // 3. Real capture: CMU walk retargeted onto the same humanoid.
      RetargetReport report;
      Clip clip = retarget(load_bvh(bvh, AxisConvention{"y", "z", 0.056444}), humanoid.skeleton, load_retarget_map(map), &report);
      clip.name = "cmu131_01_on_humanoid3d";
      show(clip, humanoid, *out, 0.0, *video, 120.0, summary);
      std::string rep = fmt::format("retarget    scale {:.3f}; end-effector error (mean/max m):", report.scale);
      for (const EffectorError& e : report.effectors) rep += fmt::format(" {} {:.3f}/{:.3f};", e.name, e.mean, e.max);
      fmt::print("{}\n", rep);
      summary += rep + "\n";
    } else {
      spdlog::info("shared data not found (../shared/data or $MIMIC_DATA): showing the built-in clip only");
    }
    write_file_atomic(*out / "summary.txt", summary);
    spdlog::info("wrote clips (.mclip), pictures (.svg), videos (.mp4) and summary.txt to {}", out->string());
  });
}

}  // namespace mimic::app
