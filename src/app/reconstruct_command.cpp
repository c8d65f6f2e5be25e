// `mimic reconstruct`: keypoints to a clip on a character (seed 003 §5, docs/video.md).
#include <spdlog/spdlog.h>

#include <cmath>
#include <map>
#include <memory>
#include <sstream>

#include "app/commands.hpp"
#include "core/error.hpp"
#include "core/file_io.hpp"
#include "core/yaml_reader.hpp"
#include "video/pose_error.hpp"
#include "video/reconstruct.hpp"

namespace mimic::app {

namespace {

struct ReconstructArgs {
  std::filesystem::path input, character, output, raw, truth, json, map;
  std::string image_size;
  double fps = 30.0;
  ReconstructionOptions opts;
};

std::string frame_list(const std::vector<int>& frames) {
  std::string s = "[";
  for (std::size_t i = 0; i < frames.size(); ++i) s += (i ? ", " : "") + std::to_string(frames[i]);
  return s + "]";
}

std::string terms_json(const ReconstructionTerms& t) {
  return "{\"l2d\": " + json_number(t.l2d) + ", \"l3d\": " + json_number(t.l3d) + ", \"lsm\": " + json_number(t.lsm) + "}";
}

KeypointReadOptions read_options(const ReconstructArgs& a) {
  KeypointReadOptions r;
  r.fps = a.fps;
  if (!a.image_size.empty()) {
    std::istringstream in(a.image_size);
    char x = 0;
    if (!(in >> r.width >> x >> r.height) || x != 'x' || r.width <= 0 || r.height <= 0 || !in.eof())
      throw Error("--image-size " + a.image_size + ": expected WIDTHxHEIGHT in pixels, e.g. 1920x1080");
  }
  return r;
}

void run(const ReconstructArgs& a) {
  const KeypointTrack track = load_keypoints(a.input, read_options(a));
  const Skeleton character = load_target_skeleton(a.character);
  const KeypointMap map = a.map.empty() ? KeypointMap{} : load_keypoint_map(a.map);
  spdlog::info("{}: {} frames of {} keypoints; reconstructing on {} ({} joints, {} degrees of freedom)", a.input.string(), track.num_frames(),
               track.names.size(), a.character.string(), character.num_joints(), character.dof_count());
  Reconstruction r = reconstruct_motion(track, character, map, a.opts);
  const ReconstructionReport& rep = r.report;
  r.reconstructed.name = a.output.stem().string();
  write_motion(r.reconstructed, a.output);
  if (!a.raw.empty()) write_motion(r.raw, a.raw);
  fmt::print("frames: {} reconstructed from track frame {}; {} could not be fitted ({} bridged, {} cut)\n", r.reconstructed.num_frames(),
             rep.first_frame, rep.unfit.size(), rep.bridged.size(), rep.cut.size());
  if (!rep.unused_keypoints.empty()) fmt::print("keypoints not on the character (unused): {}\n", fmt::join(rep.unused_keypoints, ", "));
  fmt::print("terms (unweighted)      2D (L1)   3D (rad)  smoothness (m^2)\n");
  fmt::print("  raw estimate        {:9.3f} {:9.3f} {:9.4f}\n", rep.raw.l2d, rep.raw.l3d, rep.raw.lsm);
  fmt::print("  reconstruction      {:9.3f} {:9.3f} {:9.4f}\n", rep.reconstructed.l2d, rep.reconstructed.l3d, rep.reconstructed.lsm);
  fmt::print("weights: w2D {} w3D {} wsm {}; mean w_t {:.3f}\n", a.opts.w2d, a.opts.w3d, a.opts.wsm, rep.mean_weight_3d);
  fmt::print("time: {:.1f} s (raw estimate {} iterations, {:.1f} s; reconstruction {} iterations)\n", rep.seconds, rep.raw_iterations,
             rep.raw_seconds, rep.iterations);
  fmt::print("ground: {}\n", rep.ground_fitted ? fmt::format("fitted to the feet, the camera looking {:.1f} degrees {} it", std::abs(rep.camera_pitch_deg), rep.camera_pitch_deg < 0 ? "down at" : "up from")
                                              : std::string("the feet never spread enough to show the camera's tilt; a level camera assumed"));
  std::string truth_json;
  if (!a.truth.empty()) {
    LoadOptions load;  // a DeepMimic truth is read on the character when that is DeepMimic's too
    if (a.character.extension() == ".txt") load.character = a.character;
    const Clip truth = load_motion(a.truth, load);
    const double start = rep.first_frame / track.fps;
    const PoseErrors raw = pose_errors(r.raw, truth, start), rec = pose_errors(r.reconstructed, truth, start);
    const double truth_jitter = jitter(truth);
    fmt::print("against {} ({} frames, {} joints)   raw      reconstructed\n", a.truth.string(), rec.frames, rec.joints);
    fmt::print("  MPJPE (m)              {:8.4f} {:8.4f}\n", raw.mpjpe, rec.mpjpe);
    fmt::print("  PA-MPJPE (m)           {:8.4f} {:8.4f}\n", raw.pa_mpjpe, rec.pa_mpjpe);
    fmt::print("  jitter (m/s^2)         {:8.2f} {:8.2f}   (the clip's own: {:.2f})\n", raw.jitter, rec.jitter, truth_jitter);
    truth_json = ",\n \"truth\": {\"clip\": " + json_string(a.truth.string()) + ", \"frames\": " + std::to_string(rec.frames) +
                 ", \"joints\": " + std::to_string(rec.joints) + "},\n \"mpjpe_m\": {\"raw\": " + json_number(raw.mpjpe) +
                 ", \"reconstructed\": " + json_number(rec.mpjpe) + "},\n \"pa_mpjpe_m\": {\"raw\": " + json_number(raw.pa_mpjpe) +
                 ", \"reconstructed\": " + json_number(rec.pa_mpjpe) + "},\n \"jitter\": {\"raw\": " + json_number(raw.jitter) +
                 ", \"reconstructed\": " + json_number(rec.jitter) + ", \"truth\": " + json_number(truth_jitter) + "}";
  }
  if (!a.json.empty()) {
    const std::string j = "{\"keypoints\": " + json_string(a.input.string()) + ", \"character\": " + json_string(a.character.string()) +
                          ", \"clip\": " + json_string(a.output.string()) + ",\n \"frames\": " + std::to_string(r.reconstructed.num_frames()) +
                          ", \"first_frame\": " + std::to_string(rep.first_frame) + ", \"unfit\": " + frame_list(rep.unfit) +
                          ", \"bridged\": " + frame_list(rep.bridged) + ", \"cut\": " + frame_list(rep.cut) +
                          ",\n \"weights\": {\"w2d\": " + json_number(a.opts.w2d) + ", \"w3d\": " + json_number(a.opts.w3d) +
                          ", \"wsm\": " + json_number(a.opts.wsm) + "}, \"mean_weight_3d\": " + json_number(rep.mean_weight_3d) +
                          ",\n \"terms\": {\"raw\": " + terms_json(rep.raw) + ", \"reconstructed\": " + terms_json(rep.reconstructed) + "}" +
                          ",\n \"ground_fitted\": " + (rep.ground_fitted ? "true" : "false") + ", \"camera_pitch_deg\": " +
                          json_number(rep.camera_pitch_deg) + ", \"iterations\": " + std::to_string(rep.iterations) +
                          ", \"seconds\": " + json_number(rep.seconds) + truth_json + "}\n";
    write_file_atomic(a.json, j);
  }
  spdlog::info("wrote {}", a.output.string());
}

}  // namespace

bool is_reconstruction_report(const std::filesystem::path& path) {
  const YamlReader r(path.string(), '"');
  const YAML::Node root = r.parse(read_text_file(path), path.string() + ": not a JSON file");
  return root.IsMap() && root["terms"] && root["keypoints"];
}

std::string reconstruction_table(const std::vector<std::filesystem::path>& inputs, const std::vector<std::string>& names) {
  std::string text =
      "| clip | frames | MPJPE raw (m) | MPJPE reconstructed (m) | PA-MPJPE raw (m) | PA-MPJPE reconstructed (m) | jitter raw (m/s²) | "
      "jitter reconstructed (m/s²) | jitter of the truth (m/s²) | unfit frames | seconds |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const YamlReader r(inputs[i].string(), '"');
    const YAML::Node root = r.parse(read_text_file(inputs[i]), inputs[i].string() + ": not a reconstruction report (mimic reconstruct --json)");
    if (!root.IsMap() || !root["mpjpe_m"])
      throw Error(inputs[i].string() + ": not a reconstruction report made with --truth (no \"mpjpe_m\")");
    auto pair = [&](const char* key) {
      const YAML::Node n = r.member(root, key, "the report");
      return std::pair{r.number(n, "raw", std::string("\"") + key + "\""), r.number(n, "reconstructed", std::string("\"") + key + "\"")};
    };
    const auto [m0, m1] = pair("mpjpe_m");
    const auto [p0, p1] = pair("pa_mpjpe_m");
    const auto [j0, j1] = pair("jitter");
    const double jt = r.number(r.member(root, "jitter", "the report"), "truth", "\"jitter\"");
    const std::string name = names.empty() ? r.text(r.member(r.member(root, "truth", "the report"), "clip", "\"truth\""), "\"clip\"") : names[i];
    text += fmt::format("| {} | {} | {:.4f} | {:.4f} | {:.4f} | {:.4f} | {:.1f} | {:.1f} | {:.1f} | {} | {:.1f} |\n", name,
                        r.integer(r.member(root, "frames", "the report"), "\"frames\""), m0, m1, p0, p1, j0, j1, jt,
                        r.sequence(root, "unfit", "the report").size(), r.number(root, "seconds", "the report"));
  }
  return text;
}

void add_reconstruct_command(CLI::App& app) {
  auto args = std::make_shared<ReconstructArgs>();
  CLI::App* cmd = app.add_subcommand("reconstruct", "a clip on a character from a person's keypoints (mimic video keypoints, OpenPose, COCO): "
                                                    "2D, 3D and smoothness terms optimised together (docs/video.md)");
  cmd->add_option("keypoints", args->input, "keypoint file (mimic's JSON, OpenPose's per-frame JSON or its folder, COCO keypoints)")
      ->required()
      ->check(CLI::ExistingPath);
  cmd->add_option("--character", args->character, "the character: DeepMimic character file or a .mclip whose skeleton to use")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", args->output, "the reconstructed clip (.mclip or DeepMimic .txt)")->required();
  cmd->add_option("--raw", args->raw, "also write the raw per-frame estimate as a clip");
  cmd->add_option("--map", args->map, "keypoint map (YAML: keypoints: {name: joint or site}); default: keypoints named like joints")
      ->check(CLI::ExistingFile);
  cmd->add_option("--truth", args->truth, "the true clip: MPJPE, PA-MPJPE and jitter of the raw estimate and the reconstruction against it")
      ->check(CLI::ExistingFile);
  cmd->add_option("--json", args->json, "write the report as JSON");
  cmd->add_option("--image-size", args->image_size, "WIDTHxHEIGHT, for keypoint files that do not hold it (OpenPose)");
  cmd->add_option("--fps", args->fps, "frame rate, for keypoint files that do not hold it")->capture_default_str();
  ReconstructionOptions& o = args->opts;
  cmd->add_option("--fov", o.fov_deg, "vertical field of view in degrees (default: the file's, else 55)");
  cmd->add_option("--w2d", o.w2d, "weight of the 2D term")->capture_default_str()->check(CLI::NonNegativeNumber);
  cmd->add_option("--w3d", o.w3d, "weight of the 3D term")->capture_default_str()->check(CLI::NonNegativeNumber);
  cmd->add_option("--wsm", o.wsm, "weight of the smoothness term")->capture_default_str()->check(CLI::NonNegativeNumber);
  cmd->add_option("--smoothness", o.smoothness, "what the smoothness term penalises: velocity (seed 003's) or acceleration")
      ->transform(CLI::CheckedTransformer(std::map<std::string, Smoothness>{{"velocity", Smoothness::Velocity}, {"acceleration", Smoothness::Acceleration}}))
      ->capture_default_str();
  cmd->add_option("--iterations", o.max_iterations, "most optimiser iterations")->capture_default_str()->check(CLI::Range(1, 100000));
  cmd->add_flag("--verbose", o.verbose, "print the optimiser's iterations");
  cmd->callback([args] { run(*args); });
}

}  // namespace mimic::app
