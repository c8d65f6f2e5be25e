// mimic demo: the README's first command. Today: motion import, retargeting and pictures.
#include <spdlog/spdlog.h>

#include "app/commands.hpp"
#include "core/file_io.hpp"
#include "motion/builtin.hpp"
#include "motion/bvh.hpp"
#include "motion/deepmimic.hpp"
#include "motion/retarget.hpp"
#include "core/build_paths.hpp"

namespace mimic::app {

namespace {

void show(const Clip& clip, const std::filesystem::path& dir, std::string& summary) {
  const std::string text = clip_summary(clip);
  fmt::print("{}\n", text);
  summary += text + "\n";
  write_motion(clip, dir / (clip.name + ".mclip"));
  write_motion(clip, dir / (clip.name + ".svg"));
}

}  // namespace

void add_demo_command(CLI::App& app) {
  auto out = std::make_shared<std::filesystem::path>("out/demo");
  CLI::App* demo = app.add_subcommand("demo", "run mimic's showcase on built-in (and, if present, shared) motion");
  demo->add_option("-o,--output", *out, "output directory")->capture_default_str();
  demo->callback([out] {
    std::string summary;
    // 1. Motion the project authors itself: always available.
    show(builtin_jumping_jack(), *out, summary);
    // 2. Real capture: CMU walk retargeted onto the DeepMimic humanoid, when ../shared is here.
    const auto data = shared_data_dir();
    const auto bvh = data / "cmu-bvh/131_01.bvh", ch = data / "deepmimic/characters/humanoid3d.txt";
    const auto map = std::filesystem::path(kSourceDir) / "data/retarget/cmu_to_humanoid3d.yaml";
    if (!data.empty() && std::filesystem::exists(bvh) && std::filesystem::exists(ch) && std::filesystem::exists(map)) {
      RetargetReport report;
      Clip clip = retarget(load_bvh(bvh, AxisConvention{"y", "z", 0.056444}), load_deepmimic_character(ch).skeleton,
                           load_retarget_map(map), &report);
      clip.name = "cmu131_01_on_humanoid3d";
      show(clip, *out, summary);
      std::string rep = fmt::format("retarget    scale {:.3f}; end-effector error (mean/max m):", report.scale);
      for (const EffectorError& e : report.effectors) rep += fmt::format(" {} {:.3f}/{:.3f};", e.name, e.mean, e.max);
      fmt::print("{}\n", rep);
      summary += rep + "\n";
    } else {
      spdlog::info("shared data not found (../shared/data or $MIMIC_DATA): showing the built-in clip only");
    }
    write_file_atomic(*out / "summary.txt", summary);
    spdlog::info("wrote clips (.mclip), pictures (.svg) and summary.txt to {}", out->string());
  });
}

}  // namespace mimic::app
