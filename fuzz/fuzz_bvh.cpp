// Fuzz target: BVH import. Any input must parse into a valid clip or raise mimic::Error, never crash.
#include <cstdint>
#include <string_view>

#include "core/error.hpp"
#include "fuzz_common.hpp"
#include "fuzz_seeds.hpp"
#include "motion/bvh.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  mimic::Clip clip;
  try {
    clip = mimic::parse_bvh(mimic::fuzz::as_text(data, size), "fuzz.bvh");
  } catch (const mimic::Error&) {
    return 0;
  }
  mimic::fuzz::require_valid(clip, data, size);  // what a reader accepts must be a valid clip
  return 0;
}

std::vector<std::string> MimicFuzzSeeds() {
  auto seeds = mimic::fuzz::shared_files({"cmu-bvh/131_01.bvh"}, 40000);
  seeds.push_back(
      "HIERARCHY\nROOT Hips\n{\n OFFSET 0 0 0\n CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"
      " JOINT Knee\n {\n  OFFSET 0 -10 0\n  CHANNELS 1 Xrotation\n  End Site\n  {\n   OFFSET 0 -10 0\n  }\n }\n}\n"
      "MOTION\nFrames: 2\nFrame Time: 0.033333\n0 90 0 0 0 0 10\n1 90 0 5 0 0 20\n");
  return seeds;
}
