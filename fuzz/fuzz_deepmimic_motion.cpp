// Fuzz target: DeepMimic motion import against a small built-in character (and DeepMimic's
// humanoid when the shared data is present, so that its motions are seeds that parse). Any input
// must parse into a valid clip or raise mimic::Error, never crash.
#include <algorithm>
#include <cstdint>
#include <string_view>
#include <vector>

#include "core/error.hpp"
#include "fuzz_common.hpp"
#include "fuzz_seeds.hpp"
#include "motion/deepmimic.hpp"

namespace {

// Root, spherical chest, revolute knee, fixed wrist: rows of 1 + 7 + 4 + 1 = 13 values.
const char kCharacter[] =
    "{\"Skeleton\": {\"Joints\": [\n"
    "{\"ID\": 0, \"Name\": \"root\", \"Type\": \"none\", \"Parent\": -1},\n"
    "{\"ID\": 1, \"Name\": \"chest\", \"Type\": \"spherical\", \"Parent\": 0, \"AttachX\": 0, \"AttachY\": 0.2, \"AttachZ\": 0,"
    " \"AttachThetaX\": 0, \"AttachThetaY\": 0, \"AttachThetaZ\": 0},\n"
    "{\"ID\": 2, \"Name\": \"knee\", \"Type\": \"revolute\", \"Parent\": 0, \"AttachX\": 0, \"AttachY\": -0.4, \"AttachZ\": 0.08,"
    " \"AttachThetaX\": 0, \"AttachThetaY\": 0, \"AttachThetaZ\": 0},\n"
    "{\"ID\": 3, \"Name\": \"wrist\", \"Type\": \"fixed\", \"Parent\": 1, \"AttachX\": 0.3, \"AttachY\": 0, \"AttachZ\": 0,"
    " \"AttachThetaX\": 0, \"AttachThetaY\": 0, \"AttachThetaZ\": 0}\n"
    "]}}\n";

const std::vector<mimic::Skeleton>& skeletons() {
  static const std::vector<mimic::Skeleton> all = [] {
    std::vector<mimic::Skeleton> out{mimic::parse_deepmimic_character(kCharacter, "fuzz_character.txt").skeleton};
    for (const std::string& text : mimic::fuzz::shared_files({"deepmimic/characters/humanoid3d.txt"}, 1 << 20))
      out.push_back(mimic::parse_deepmimic_character(text, "humanoid3d.txt").skeleton);
    return out;
  }();
  return all;
}

// The first `n` frames of a DeepMimic motion written one frame per line, closed again (a short
// seed keeps the fuzzer fast); other layouts are returned whole.
std::string first_frames(const std::string& text, int n) {
  std::size_t pos = 0;
  for (int rows = 0; pos < text.size();) {
    const std::size_t eol = std::min(text.find('\n', pos), text.size());
    const std::string_view line(text.data() + pos, eol - pos);
    if (line.size() > 1 && line[0] == '[' && ++rows == n) {
      const std::size_t end = line.find(']');
      return end == std::string_view::npos ? text : text.substr(0, pos + end + 1) + "\n]\n}\n";
    }
    pos = eol + 1;
  }
  return text;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  for (const mimic::Skeleton& sk : skeletons()) {
    mimic::Clip clip;
    try {
      clip = mimic::parse_deepmimic_motion(mimic::fuzz::as_text(data, size), "fuzz_motion.txt", sk);
    } catch (const mimic::Error&) {
      continue;
    }
    mimic::fuzz::require_valid(clip, data, size);  // what a reader accepts must be a valid clip
  }
  return 0;
}

std::vector<std::string> MimicFuzzSeeds() {
  std::vector<std::string> seeds;
  for (const std::string& walk : mimic::fuzz::shared_files({"deepmimic/motions/humanoid3d_walk.txt"}, 1 << 20))
    seeds.push_back(first_frames(walk, 5));
  seeds.push_back(
      "{\n\"Loop\": \"wrap\",\n\"Frames\":\n[\n"
      "[0.5, 0, 0.8, 0, 1, 0, 0, 0, 1, 0, 0, 0, -0.5],\n"
      "[0.5, 0.1, 0.81, 0, 1, 0, 0, 0, 0.8, 0.6, 0, 0, -0.6],\n"
      "[0, 0.2, 0.82, 0, 1, 0, 0, 0, 0.6, 0, 0.8, 0, -0.7]\n]\n}\n");
  // Unequal durations (resampled), no loop, one frame.
  seeds.push_back(
      "{\"Loop\": \"none\", \"Frames\": [[0.25, 0, 0.8, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0], [0.5, 0, 0.8, 0.1, 0.7071, 0, 0.7071, 0,"
      " 1, 0, 0, 0, 1], [0.125, 0, 0.8, 0.2, 0, 0, 1, 0, 0, 0, 0, 1, 2], [0, 1, 1, 1, 1, 0, 0, 0, 1, 0, 0, 0, 3]]}\n");
  seeds.push_back("{\"Frames\": [[0.0333, 0, 0.9, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0.1]]}\n");
  return seeds;
}
