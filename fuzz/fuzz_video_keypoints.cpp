// Fuzz target: mimic's keypoint JSON. Any input must parse or raise mimic::Error, never crash; a
// file that parses is valid (KeypointTrack::validate) and survives writing and reading again with
// its frames, names and image size.
#include <cstdint>
#include <string_view>

#include "core/error.hpp"
#include "fuzz_common.hpp"
#include "fuzz_seeds.hpp"
#include "video/keypoints.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  mimic::KeypointTrack track;
  try {
    track = mimic::parse_keypoints(mimic::fuzz::as_text(data, size), "fuzz.json");
  } catch (const mimic::Error&) {
    return 0;
  }
  try {
    track.validate();
    const mimic::KeypointTrack back = mimic::parse_keypoints(mimic::write_keypoints(track), "again.json");
    if (back.num_frames() != track.num_frames() || back.names != track.names || back.width != track.width || back.height != track.height)
      mimic::fuzz::fail_with_input(data, size, "a parsed track changed when written and read again");
  } catch (const mimic::Error& e) {
    mimic::fuzz::fail_with_input(data, size, std::string("a parsed track was refused when written and read again: ") + e.what());
  }
  return 0;
}

std::vector<std::string> MimicFuzzSeeds() {
  return {
      "{\"format\": \"mimic-keypoints\", \"version\": 1, \"fps\": 30, \"width\": 640, \"height\": 480, \"fov_deg\": 55,\n"
      " \"names\": [\"a\", \"b\"],\n \"frames\": [{\"pixel\": [[1, 2], [3, 4]], \"confidence\": [1, 0.5], \"world\": [[0, 0, 0], [0.1, 0.2, 0.3]]},\n"
      "  {}, {\"pixel\": [[5, 6], [7, 8]], \"confidence\": [0, 1]}]}\n",
      "{\"format\": \"mimic-keypoints\", \"version\": 1, \"fps\": 25, \"width\": 1, \"height\": 1, \"names\": [\"x\"], \"frames\": []}",
      "{\"format\": \"mimic-keypoints\", \"version\": 1, \"fps\": 25, \"width\": 1, \"height\": 1, \"names\": [\"a\\nb\\t\\\"c\\\\\"], \"frames\": []}",
  };
}
