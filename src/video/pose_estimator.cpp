#include "video/pose_estimator.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include <unistd.h>

#include "core/build_paths.hpp"
#include "core/error.hpp"
#include "core/file_io.hpp"
#include "core/yaml_reader.hpp"

namespace mimic {

namespace fs = std::filesystem;

namespace {

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// All of a command's standard output; its exit status in `status`.
std::string run_capture(const std::string& cmd, int& status) {
  std::FILE* pipe = ::popen(cmd.c_str(), "r");
  if (!pipe) throw Error("cannot start: " + cmd);
  std::string out;
  char buf[4096];
  while (std::size_t n = std::fread(buf, 1, sizeof buf, pipe)) out.append(buf, n);
  status = ::pclose(pipe);
  return out;
}

struct VideoInfo {
  int width = 0, height = 0;
  double fps = 0;
};

VideoInfo probe(const fs::path& video) {
  int status = 0;
  const std::string out = run_capture("ffprobe -v error -select_streams v:0 -show_entries stream=width,height,avg_frame_rate -of csv=p=0 " +
                                          shell_quote(video.string()) + " 2>/dev/null",
                                      status);
  VideoInfo v;
  long num = 0, den = 0;
  if (status != 0 || std::sscanf(out.c_str(), "%d,%d,%ld/%ld", &v.width, &v.height, &num, &den) != 4 || v.width <= 0 || v.height <= 0 || num <= 0 ||
      den <= 0)
    throw Error(video.string() + ": not a video ffmpeg can read (ffprobe found no video stream)");
  v.fps = static_cast<double>(num) / static_cast<double>(den);
  return v;
}

fs::path sidecar_dir(const PoseEstimatorOptions& o) {
  if (!o.sidecar.empty()) return o.sidecar;
  if (const char* env = std::getenv("MIMIC_POSE_DIR"); env && *env) return env;
  return fs::path(kSourceDir) / "tools" / "pose";
}

}  // namespace

const std::vector<std::string>& blazepose_names() {
  static const std::vector<std::string> names = {
      "nose", "left_eye_inner", "left_eye", "left_eye_outer", "right_eye_inner", "right_eye", "right_eye_outer", "left_ear", "right_ear",
      "mouth_left", "mouth_right", "left_shoulder", "right_shoulder", "left_elbow", "right_elbow", "left_wrist", "right_wrist",
      "left_pinky", "right_pinky", "left_index", "right_index", "left_thumb", "right_thumb", "left_hip", "right_hip", "left_knee",
      "right_knee", "left_ankle", "right_ankle", "left_heel", "right_heel", "left_foot_index", "right_foot_index"};
  return names;
}

KeypointTrack estimate_keypoints(const fs::path& video, const PoseEstimatorOptions& o) {
  if (!fs::is_regular_file(video)) throw Error(video.string() + ": not found");
  if (o.variant != "lite" && o.variant != "full" && o.variant != "heavy")
    throw Error("pose model variant '" + o.variant + "': expected lite, full or heavy");
  const fs::path dir = sidecar_dir(o);
  for (const fs::path& need : {dir / "pose.mjs", dir / "node_modules" / "@tensorflow" / "tfjs-backend-wasm", dir / "models" / ("blazepose-" + o.variant + ".bin")})
    if (!fs::exists(need))
      throw Error("the pose estimator is not installed: " + need.string() + " is missing (scripts/setup.sh installs it into tools/pose)");
  const VideoInfo info = probe(video);
  const fs::path log = fs::temp_directory_path() / ("mimic_pose_" + std::to_string(::getpid()) + ".log");
  const std::string cmd = "ffmpeg -v error -nostdin -i " + shell_quote(video.string()) + " -f rawvideo -pix_fmt rgb24 - 2>" +
                          shell_quote(log.string() + ".ffmpeg") + " | node " + shell_quote((dir / "pose.mjs").string()) + " --raw " +
                          std::to_string(info.width) + "x" + std::to_string(info.height) + " --variant " + o.variant + " 2>" +
                          shell_quote(log.string());
  KeypointTrack t;
  t.source = video.string();
  t.fps = info.fps;
  t.width = info.width, t.height = info.height;
  t.fov_deg = o.fov_deg;
  t.names = blazepose_names();
  const std::size_t n = t.names.size();
  std::FILE* pipe = ::popen(cmd.c_str(), "r");
  if (!pipe) throw Error("cannot start the pose estimator: " + cmd);
  std::string line;
  char buf[8192];
  int found = 0;
  auto take = [&](const std::string& text) {
    const std::string where = video.string() + ": the pose estimator's frame " + std::to_string(t.frames.size());
    const YamlReader r(where, '"');
    const YAML::Node f = r.parse(text, where + ": not JSON");
    KeypointFrame frame;
    const YAML::Node seen = f["found"];
    if (seen && seen.IsScalar() && seen.Scalar() == "true" && f["keypoints"] && f["world"]) {
      const YAML::Node kp = f["keypoints"], w = f["world"];
      if (!kp.IsSequence() || kp.size() != n || !w.IsSequence() || w.size() != n) r.fail(f, "expected 33 keypoints and 33 world points");
      for (std::size_t k = 0; k < n; ++k) {
        frame.pixel.emplace_back(r.number(kp[k][0], "x"), r.number(kp[k][1], "y"));
        frame.confidence.push_back(std::clamp(r.number(kp[k][3], "visibility"), 0.0, 1.0));
        frame.world.push_back(r.vec<3>(w[k], "world"));
      }
      ++found;
    }
    t.frames.push_back(std::move(frame));
    if (o.progress && t.frames.size() % 30 == 0) o.progress(static_cast<int>(t.frames.size()));
  };
  try {
    while (std::fgets(buf, sizeof buf, pipe)) {
      line += buf;
      if (!line.empty() && line.back() == '\n') take(line), line.clear();
    }
    if (!line.empty()) take(line);
  } catch (...) {
    ::pclose(pipe);
    throw;
  }
  const int status = ::pclose(pipe);
  std::string messages;
  for (const char* suffix : {"", ".ffmpeg"}) {
    std::error_code ec;
    if (fs::exists(log.string() + suffix, ec)) {
      try {
        messages += read_text_file(log.string() + suffix);
      } catch (const Error&) {
      }
      fs::remove(log.string() + suffix, ec);
    }
  }
  if (status != 0)
    throw Error(video.string() + ": the pose estimator failed after " + std::to_string(t.frames.size()) + " frames (exit status " +
                std::to_string(status) + "): " + messages);
  if (t.frames.empty()) throw Error(video.string() + ": ffmpeg decoded no frames");
  if (found == 0) throw Error(video.string() + ": no person found in any of its " + std::to_string(t.frames.size()) + " frames");
  t.validate();
  return t;
}

}  // namespace mimic
