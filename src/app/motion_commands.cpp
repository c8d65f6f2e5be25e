// mimic motion info|convert|mirror|retarget|plot
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "app/commands.hpp"
#include "core/error.hpp"
#include "core/file_io.hpp"
#include "motion/clip_io.hpp"
#include "motion/deepmimic.hpp"
#include "motion/kinematics.hpp"
#include "motion/mirror.hpp"
#include "motion/resample.hpp"
#include "motion/retarget.hpp"
#include "motion/retarget_maps.hpp"
#include "render/clip_svg.hpp"

namespace mimic::app {

void add_load_options(CLI::App& cmd, LoadOptions& opts) {
  cmd.add_option("--character", opts.character, "DeepMimic character file for a .txt motion (default: guessed from the name)");
  cmd.add_option("--asf", opts.asf, "ASF skeleton for an .amc motion (default: guessed from the name)");
  cmd.add_option("--up", opts.axes.up, "BVH: source up axis (x, y, z, -z, ...)")->capture_default_str();
  cmd.add_option("--forward", opts.axes.forward, "BVH: axis the character faces at rest")->capture_default_str();
  cmd.add_option("--scale", opts.axes.scale, "BVH: metres per file unit (CMU BVH: 0.056444)")->capture_default_str();
  cmd.add_option("--amc-fps", opts.amc_fps, "AMC: frame rate (not stored in AMC files)")->capture_default_str();
}

std::string clip_summary(const Clip& clip) {
  double root_lo = std::numeric_limits<double>::infinity(), root_hi = -root_lo, lowest = root_lo, highest = -root_lo;
  LinkFrames fk;
  for (const Pose& p : clip.frames) {
    root_lo = std::min(root_lo, p.root_pos.z());
    root_hi = std::max(root_hi, p.root_pos.z());
    forward_kinematics(clip.skeleton, p, fk);
    for (const auto* pts : {&fk.joint_pos, &fk.site_pos})
      for (const Vec3& x : *pts) lowest = std::min(lowest, x.z()), highest = std::max(highest, x.z());
  }
  const Vec3 travel = clip.frames.back().root_pos - clip.frames.front().root_pos;
  int spherical = 0, revolute = 0, fixed = 0;
  for (const Joint& j : clip.skeleton.joints) {
    spherical += j.type == JointType::Spherical;
    revolute += j.type == JointType::Revolute;
    fixed += j.type == JointType::Fixed;
  }
  // The three fastest joints: what the servos must reach (docs/simulation.md, pd_limit).
  const std::vector<double> speed = peak_joint_speeds(clip);
  std::vector<std::size_t> order(speed.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return speed[a] > speed[b]; });
  std::string fastest;
  for (std::size_t i = 0; i < std::min<std::size_t>(3, order.size()) && speed[order[i]] > 0; ++i)
    fastest += fmt::format("{}{} {:.1f}", i ? ", " : "", clip.skeleton.joints[order[i]].name, speed[order[i]]);
  return fmt::format(
      "clip        {}\n"
      "skeleton    {} joints ({} spherical, {} revolute, {} fixed), {} DoF, {} sites\n"
      "frames      {} at {:.3f} Hz = {:.3f} s, loop {}\n"
      "root height {:.3f} .. {:.3f} m; all points {:.3f} .. {:.3f} m\n"
      "travel      {:.3f} m on the ground over the clip, heading {:+.0f} deg\n"
      "fastest     {} rad/s (joints, frame to frame)\n",
      clip.name, clip.skeleton.num_joints(), spherical, revolute, fixed, clip.skeleton.dof_count(), clip.skeleton.sites.size(),
      clip.num_frames(), clip.fps, clip.duration(), to_string(clip.loop), root_lo, root_hi, lowest, highest,
      std::hypot(travel.x(), travel.y()),
      rad_to_deg(heading_angle(clip.frames.back().rot[0]) - heading_angle(clip.frames.front().rot[0])), fastest.empty() ? "-" : fastest);
}

RetargetMap fitting_builtin_map(const Clip& clip, const std::filesystem::path& input, const Skeleton& target, const std::filesystem::path& target_file) {
  const std::vector<std::string> fitting = builtin_maps_fitting(clip.skeleton, target);
  if (fitting.empty())
    throw Error(input.string() + ": no built-in map fits its joints onto " + target_file.string() + " (built in: " + builtin_retarget_map_list() +
                "); give --map MAP.yaml (docs/retargeting.md)");
  if (fitting.size() > 1) {
    std::string names;
    for (const std::string& n : fitting) names += (names.empty() ? "" : ", ") + n;
    throw Error(input.string() + ": several built-in maps fit (" + names + "); choose one with --map");
  }
  spdlog::info("{}: its joints are those of the built-in map {}", input.string(), fitting.front());
  return builtin_retarget_map(fitting.front());
}

std::string retarget_summary(const RetargetReport& report) {
  std::string text = fmt::format("scale {:.3f}, ground shift {:+.3f} m\nend effectors against the scaled source (m): root-relative mean, max; "
                                 "world mean, by the rotations alone -> after inverse kinematics\n",
                                 report.scale, report.ground_shift);
  for (const EffectorError& e : report.effectors)
    text += fmt::format("  {:<16} {:.3f}  {:.3f}    {:.3f} -> {:.3f}\n", e.name, e.mean, e.max, e.world_mean_before_ik, e.world_mean);
  for (const ContactReport& c : report.contacts)
    text += fmt::format("contact {:<16} {} stance frames of the source, sliding {:.3f} -> {:.3f} m/s\n", c.name, c.stance_frames,
                        c.sliding_before_ik, c.sliding);
  text += fmt::format("frames with a point below the floor: {}\n", report.frames_below_floor);
  if (report.source_turn != 0)
    text += fmt::format("the source faced {:+d} degrees from the target at rest (its forward axis is not the one given): the target was turned so\n",
                        report.source_turn);
  return text;
}

void write_motion(const Clip& clip, const std::filesystem::path& out) {
  const std::string ext = out.extension().string();
  if (ext == ".mclip") save_clip(clip, out);
  else if (ext == ".txt") write_file_atomic(out, write_deepmimic_motion(clip));
  else if (ext == ".svg") write_file_atomic(out, clip_picture_svg(clip));
  else throw Error(out.string() + ": unknown output format '" + ext + "' (expected .mclip, .txt for DeepMimic, or .svg)");
}

namespace {

struct MotionArgs {
  std::filesystem::path input, output, map, target;
  LoadOptions load;
  double fps = 0.0;
  double start = std::numeric_limits<double>::quiet_NaN(), end = std::numeric_limits<double>::quiet_NaN();
  int panels = 8;
};

}  // namespace

Skeleton load_target_skeleton(const std::filesystem::path& path) {
  if (path.extension() == ".mclip") return load_motion(path).skeleton;
  return load_deepmimic_character(path).skeleton;
}

void add_motion_commands(CLI::App& app) {
  auto args = std::make_shared<MotionArgs>();
  CLI::App* motion = app.add_subcommand("motion", "inspect, convert, mirror and retarget motion clips");
  motion->require_subcommand(1);

  CLI::App* info = motion->add_subcommand("info", "summary of a clip (.mclip, .bvh, .amc, DeepMimic .txt)");
  info->add_option("clip", args->input, "motion file")->required()->check(CLI::ExistingFile);
  add_load_options(*info, args->load);
  info->callback([args] { fmt::print("{}", clip_summary(load_motion(args->input, args->load))); });

  CLI::App* convert = motion->add_subcommand("convert", "convert a clip to .mclip, DeepMimic .txt or an .svg picture");
  convert->add_option("clip", args->input, "motion file")->required()->check(CLI::ExistingFile);
  convert->add_option("-o,--output", args->output, "output file")->required();
  convert->add_option("--fps", args->fps, "resample to this frame rate first");
  convert->add_option("--start", args->start, "keep only the frames from this many seconds in (default: the first); the result does not loop");
  convert->add_option("--end", args->end, "keep only the frames up to this many seconds in (default: the last); the result does not loop");
  add_load_options(*convert, args->load);
  convert->callback([args] {
    Clip clip = load_motion(args->input, args->load);
    if (!std::isnan(args->start) || !std::isnan(args->end)) try {
        clip = excerpt(clip, std::isnan(args->start) ? 0.0 : args->start, std::isnan(args->end) ? clip.duration() : args->end);
      } catch (const Error& e) {
        throw Error(args->input.string() + ": " + e.what());
      }
    if (args->fps > 0) clip = resample(clip, args->fps);
    write_motion(clip, args->output);
    spdlog::info("wrote {} ({} frames at {:.3f} Hz)", args->output.string(), clip.num_frames(), clip.fps);
  });

  CLI::App* mirror_cmd = motion->add_subcommand("mirror", "swap left and right");
  mirror_cmd->add_option("clip", args->input, "motion file")->required()->check(CLI::ExistingFile);
  mirror_cmd->add_option("-o,--output", args->output, "output file")->required();
  add_load_options(*mirror_cmd, args->load);
  mirror_cmd->callback([args] {
    write_motion(mirror(load_motion(args->input, args->load)), args->output);
    spdlog::info("wrote {}", args->output.string());
  });

  CLI::App* ret = motion->add_subcommand("retarget", "put a clip on another character by a joint-name map");
  ret->add_option("clip", args->input, "source motion file")->required()->check(CLI::ExistingFile);
  ret->add_option("--map", args->map,
                  "retarget map: a YAML file (docs/retargeting.md) or a built-in map's name (" + builtin_retarget_map_list() +
                      "); default: the one built-in map that fits the clip and the target");
  ret->add_option("--target", args->target, "target character: DeepMimic character file or a .mclip")->required()->check(CLI::ExistingFile);
  ret->add_option("-o,--output", args->output, "output file")->required();
  add_load_options(*ret, args->load);
  ret->callback([args] {
    RetargetReport report;
    const Clip clip = load_motion(args->input, args->load);
    const Skeleton target = load_target_skeleton(args->target);
    const RetargetMap map = args->map.empty() ? fitting_builtin_map(clip, args->input, target, args->target) : load_retarget_map_or_builtin(args->map.string());
    const Clip out = retarget(clip, target, map, &report);
    write_motion(out, args->output);
    fmt::print("{}", retarget_summary(report));
    spdlog::info("wrote {}", args->output.string());
  });

  CLI::App* plot = motion->add_subcommand("plot", "draw a clip as an SVG filmstrip with height curves");
  plot->add_option("clip", args->input, "motion file")->required()->check(CLI::ExistingFile);
  plot->add_option("-o,--output", args->output, "output .svg")->required();
  plot->add_option("--panels", args->panels, "frames to draw")->capture_default_str()->check(CLI::Range(1, 64));
  add_load_options(*plot, args->load);
  plot->callback([args] {
    write_file_atomic(args->output, clip_picture_svg(load_motion(args->input, args->load), ClipPictureOptions{args->panels, 180}));
    spdlog::info("wrote {}", args->output.string());
  });
}

}  // namespace mimic::app
