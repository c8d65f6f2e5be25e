#include "video/keypoints.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "core/error.hpp"
#include "core/json_text.hpp"
#include "core/file_io.hpp"
#include "core/yaml_reader.hpp"

namespace mimic {

namespace fs = std::filesystem;

namespace {

constexpr const char* kFormat = "mimic-keypoints";

// OpenPose's layouts (its output documentation), by the number of keypoints.
const std::vector<std::string> kBody25 = {"Nose", "Neck", "RShoulder", "RElbow", "RWrist", "LShoulder", "LElbow", "LWrist", "MidHip",
                                          "RHip", "RKnee", "RAnkle", "LHip", "LKnee", "LAnkle", "REye", "LEye", "REar", "LEar",
                                          "LBigToe", "LSmallToe", "LHeel", "RBigToe", "RSmallToe", "RHeel"};
const std::vector<std::string> kOpenPoseCoco18 = {"Nose", "Neck", "RShoulder", "RElbow", "RWrist", "LShoulder", "LElbow", "LWrist", "RHip",
                                                  "RKnee", "RAnkle", "LHip", "LKnee", "LAnkle", "REye", "LEye", "REar", "LEar"};
// COCO's 17 person keypoints (the dataset's "categories"), used where a file does not list them.
const std::vector<std::string> kCoco17 = {"nose", "left_eye", "right_eye", "left_ear", "right_ear", "left_shoulder", "right_shoulder",
                                          "left_elbow", "right_elbow", "left_wrist", "right_wrist", "left_hip", "right_hip",
                                          "left_knee", "right_knee", "left_ankle", "right_ankle"};

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// Flat [x, y, c, x, y, c, ...] lists (OpenPose's and COCO's) into one frame of `n` keypoints.
// A confidence above 1 (COCO's visibility flag 2) counts as 1.
KeypointFrame frame_of_triples(const YamlReader& r, const YAML::Node& list, std::size_t n, const std::string& what) {
  if (!list.IsSequence() || list.size() != 3 * n)
    r.fail(list, what + ": expected " + std::to_string(3 * n) + " numbers (x, y, confidence for each of " + std::to_string(n) +
                     " keypoints), found " + (list.IsSequence() ? std::to_string(list.size()) : std::string("no list")));
  KeypointFrame f;
  for (std::size_t k = 0; k < n; ++k) {
    const double x = r.number(list[3 * k], what), y = r.number(list[3 * k + 1], what), c = r.number(list[3 * k + 2], what);
    if (c < 0) r.fail(list, what + ": keypoint " + std::to_string(k) + " has a negative confidence");
    f.pixel.emplace_back(x, y);
    f.confidence.push_back(std::min(c, 1.0));
  }
  return f;
}

// The person of an OpenPose frame with the largest summed confidence (a frame with nobody: empty).
KeypointFrame openpose_frame(const fs::path& file, std::vector<std::string>& names) {
  const YamlReader r(file.string(), '"');
  const YAML::Node root = r.parse(read_text_file(file), file.string() + ": not an OpenPose keypoint file");
  const YAML::Node people = r.sequence(root, "people", "the file");
  KeypointFrame best;
  double best_sum = -1;
  for (std::size_t p = 0; p < people.size(); ++p) {
    const YAML::Node list = r.member(people[p], "pose_keypoints_2d", "person " + std::to_string(p));
    const std::vector<std::string>& layout = list.IsSequence() && list.size() == 3 * kOpenPoseCoco18.size() ? kOpenPoseCoco18 : kBody25;
    if (!names.empty() && names != layout) r.fail(list, "person " + std::to_string(p) + ": another keypoint layout than the first frame's");
    names = layout;
    KeypointFrame f = frame_of_triples(r, list, layout.size(), "person " + std::to_string(p) + " \"pose_keypoints_2d\"");
    double sum = 0;
    for (double c : f.confidence) sum += c;
    if (sum > best_sum) best = std::move(f), best_sum = sum;
  }
  return best;
}

KeypointTrack read_openpose(const fs::path& path, const KeypointReadOptions& opts) {
  std::vector<fs::path> files;
  if (fs::is_directory(path)) {
    for (const auto& e : fs::directory_iterator(path))
      if (e.path().extension() == ".json") files.push_back(e.path());
    std::sort(files.begin(), files.end());  // OpenPose numbers its files with leading zeros
    if (files.empty()) throw Error(path.string() + ": a folder without .json files (expected OpenPose's per-frame *_keypoints.json)");
  } else {
    files.push_back(path);
  }
  KeypointTrack t;
  t.source = path.string();
  for (const fs::path& f : files) t.frames.push_back(openpose_frame(f, t.names));
  if (t.names.empty()) throw Error(path.string() + ": no person in any frame");
  for (KeypointFrame& f : t.frames)  // frames with nobody: the layout's size, nothing seen
    if (f.empty()) f.pixel.assign(t.names.size(), Vec2::Zero()), f.confidence.assign(t.names.size(), 0.0);
  t.fps = opts.fps;
  t.width = opts.width, t.height = opts.height;
  return t;
}

KeypointTrack read_coco(const YamlReader& r, const YAML::Node& root, const KeypointReadOptions& opts) {
  KeypointTrack t;
  t.source = r.source();
  t.fps = opts.fps;
  t.width = opts.width, t.height = opts.height;
  t.names = kCoco17;
  // (A YAML::Node assigned to another writes into the node it refers to: chosen once, here.)
  const YAML::Node annotations = root.IsMap() ? r.sequence(root, "annotations", "the COCO file") : root;
  std::map<long, std::size_t> frame_of_image;  // image id -> frame, in the order of the ids
  if (root.IsMap()) {
    const YAML::Node images = r.sequence(root, "images", "the COCO file");
    for (std::size_t i = 0; i < images.size(); ++i) {
      frame_of_image[r.integer(r.member(images[i], "id", "image " + std::to_string(i)), "\"id\"")] = 0;
      if (i == 0 && images[i]["width"] && images[i]["height"]) {
        t.width = static_cast<int>(r.integer(images[i]["width"], "\"width\""));
        t.height = static_cast<int>(r.integer(images[i]["height"], "\"height\""));
      }
    }
    if (const YAML::Node cats = root["categories"]; cats && cats.IsSequence() && cats.size() > 0 && cats[0]["keypoints"]) {
      const YAML::Node kp = cats[0]["keypoints"];
      t.names.clear();
      for (std::size_t k = 0; k < kp.size(); ++k) t.names.push_back(r.text(kp[k], "\"categories\" \"keypoints\""));
    }
  } else {
    for (std::size_t a = 0; a < annotations.size(); ++a)
      frame_of_image[r.integer(r.member(annotations[a], "image_id", "annotation " + std::to_string(a)), "\"image_id\"")] = 0;
  }
  std::size_t next = 0;
  for (auto& [id, frame] : frame_of_image) frame = next++;
  t.frames.assign(next, KeypointFrame{});
  std::vector<double> best(next, -1.0);
  for (std::size_t a = 0; a < annotations.size(); ++a) {
    const std::string where = "annotation " + std::to_string(a);
    const long image = r.integer(r.member(annotations[a], "image_id", where), "\"image_id\"");
    const auto it = frame_of_image.find(image);
    if (it == frame_of_image.end()) r.fail(annotations[a], where + ": image " + std::to_string(image) + " is not among \"images\"");
    KeypointFrame f = frame_of_triples(r, r.member(annotations[a], "keypoints", where), t.names.size(), where + " \"keypoints\"");
    double score = 0;  // the person the detector was surest of, where one image has several
    for (double c : f.confidence) score += c;
    if (annotations[a]["score"]) score = r.number(annotations[a]["score"], where + " \"score\"");
    if (score > best[it->second]) t.frames[it->second] = std::move(f), best[it->second] = score;
  }
  for (KeypointFrame& f : t.frames)
    if (f.empty()) f.pixel.assign(t.names.size(), Vec2::Zero()), f.confidence.assign(t.names.size(), 0.0);
  return t;
}

}  // namespace

int KeypointTrack::find(const std::string& name) const {
  const auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? -1 : static_cast<int>(it - names.begin());
}

void KeypointTrack::validate() const {
  const std::string where = source.empty() ? std::string("keypoints") : source;
  if (!(fps > 0) || !std::isfinite(fps)) throw Error(where + ": the frame rate must be positive, not " + number(fps));
  if (width <= 0 || height <= 0)
    throw Error(where + ": the image size is unknown (" + std::to_string(width) + "x" + std::to_string(height) +
                "); give it with --image-size WxH");
  if (fov_deg < 0 || fov_deg >= 180) throw Error(where + ": field of view " + number(fov_deg) + " degrees, expected 0 (unknown) to 180");
  if (names.empty()) throw Error(where + ": no keypoint names");
  for (std::size_t i = 0; i < names.size(); ++i)
    for (std::size_t k = 0; k < i; ++k)
      if (names[i] == names[k]) throw Error(where + ": keypoint '" + names[i] + "' is named twice");
  for (std::size_t t = 0; t < frames.size(); ++t) {
    const KeypointFrame& f = frames[t];
    const std::string at = where + ": frame " + std::to_string(t);
    if (f.empty()) continue;
    if (f.pixel.size() != names.size() || f.confidence.size() != names.size())
      throw Error(at + " has " + std::to_string(f.pixel.size()) + " keypoints and " + std::to_string(f.confidence.size()) +
                  " confidences where the file names " + std::to_string(names.size()));
    if (!f.world.empty() && f.world.size() != names.size())
      throw Error(at + " has " + std::to_string(f.world.size()) + " 3D keypoints where the file names " + std::to_string(names.size()));
    for (std::size_t k = 0; k < names.size(); ++k) {
      if (!(f.confidence[k] >= 0 && f.confidence[k] <= 1)) throw Error(at + ", '" + names[k] + "': confidence " + number(f.confidence[k]) + " outside [0, 1]");
      if (!f.pixel[k].allFinite()) throw Error(at + ", '" + names[k] + "': a coordinate that is not a number");
      if (!f.world.empty() && !f.world[k].allFinite()) throw Error(at + ", '" + names[k] + "': a 3D coordinate that is not a number");
    }
  }
}

std::string write_keypoints(const KeypointTrack& t) {
  std::string s = "{\"format\": \"" + std::string(kFormat) + "\", \"version\": 1, \"fps\": " + number(t.fps) +
                  ", \"width\": " + std::to_string(t.width) + ", \"height\": " + std::to_string(t.height);
  if (t.fov_deg > 0) s += ", \"fov_deg\": " + number(t.fov_deg);
  s += ",\n \"names\": [";
  for (std::size_t k = 0; k < t.names.size(); ++k) s += (k ? ", " : "") + json_quoted(t.names[k]);
  s += "],\n \"frames\": [";
  for (std::size_t i = 0; i < t.frames.size(); ++i) {
    const KeypointFrame& f = t.frames[i];
    s += i ? ",\n  {" : "\n  {";
    if (!f.empty()) {
      s += "\"pixel\": [";
      for (std::size_t k = 0; k < f.pixel.size(); ++k) s += (k ? ", [" : "[") + number(f.pixel[k].x()) + ", " + number(f.pixel[k].y()) + "]";
      s += "], \"confidence\": [";
      for (std::size_t k = 0; k < f.confidence.size(); ++k) s += (k ? ", " : "") + number(f.confidence[k]);
      s += "]";
      if (!f.world.empty()) {
        s += ", \"world\": [";
        for (std::size_t k = 0; k < f.world.size(); ++k)
          s += (k ? ", [" : "[") + number(f.world[k].x()) + ", " + number(f.world[k].y()) + ", " + number(f.world[k].z()) + "]";
        s += "]";
      }
    }
    s += "}";
  }
  return s + "\n ]}\n";
}

KeypointTrack parse_keypoints(std::string_view text, const std::string& source) {
  const YamlReader r(source, '"');
  const YAML::Node root = r.parse(text, source + ": not a keypoint file (mimic's keypoint JSON)");
  if (!root.IsMap() || !root["format"] || r.text(root["format"], "\"format\"") != kFormat)
    throw Error(source + ": not a keypoint file (mimic's keypoint JSON has \"format\": \"" + kFormat + "\")");
  const long version = r.integer(r.member(root, "version", "the file"), "\"version\"");
  if (version != 1) throw Error(source + ": keypoint file version " + std::to_string(version) + "; this mimic reads version 1");
  KeypointTrack t;
  t.source = source;
  t.fps = r.number(root, "fps", "the file");
  t.width = static_cast<int>(r.integer(r.member(root, "width", "the file"), "\"width\""));
  t.height = static_cast<int>(r.integer(r.member(root, "height", "the file"), "\"height\""));
  t.fov_deg = r.number_or(root, "fov_deg", "the file", 0.0);
  const YAML::Node names = r.sequence(root, "names", "the file");
  for (std::size_t k = 0; k < names.size(); ++k) t.names.push_back(r.text(names[k], "\"names\""));
  const YAML::Node frames = r.sequence(root, "frames", "the file");
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const std::string where = "frame " + std::to_string(i);
    const YAML::Node fr = frames[i];
    if (!fr.IsMap()) r.fail(fr, where + ": expected an object");
    KeypointFrame f;
    if (fr["pixel"]) {
      const YAML::Node px = r.sequence(fr, "pixel", where), cf = r.sequence(fr, "confidence", where);
      for (std::size_t k = 0; k < px.size(); ++k) f.pixel.push_back(r.vec<2>(px[k], where + " \"pixel\""));
      for (std::size_t k = 0; k < cf.size(); ++k) f.confidence.push_back(r.number(cf[k], where + " \"confidence\""));
      if (fr["world"]) {
        const YAML::Node w = r.sequence(fr, "world", where);
        for (std::size_t k = 0; k < w.size(); ++k) f.world.push_back(r.vec<3>(w[k], where + " \"world\""));
      }
    }
    t.frames.push_back(std::move(f));
  }
  t.validate();
  return t;
}

void save_keypoints(const KeypointTrack& track, const fs::path& path) {
  track.validate();
  write_file_atomic(path, write_keypoints(track));
}

KeypointTrack load_keypoints(const fs::path& path, const KeypointReadOptions& opts) {
  if (!fs::exists(path)) throw Error(path.string() + ": not found");
  KeypointTrack t;
  if (fs::is_directory(path)) {
    t = read_openpose(path, opts);
  } else {
    const std::string text = read_text_file(path);
    const YamlReader r(path.string(), '"');
    const YAML::Node root = r.parse(text, path.string() + ": not a keypoint file (JSON)");
    if (root.IsMap() && root["format"]) return parse_keypoints(text, path.string());
    if (root.IsMap() && root["people"]) t = read_openpose(path, opts);
    else if ((root.IsMap() && root["annotations"]) || (root.IsSequence() && root.size() > 0 && root[0].IsMap() && root[0]["keypoints"]))
      t = read_coco(r, root, opts);
    else
      throw Error(path.string() + ": not a keypoint file mimic reads (mimic's keypoint JSON, OpenPose's per-frame JSON, COCO keypoints)");
  }
  t.validate();
  return t;
}

}  // namespace mimic
