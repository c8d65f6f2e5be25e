// Fuzz target: mimic's native clip format. Any input must parse into a valid clip or raise
// mimic::Error, never crash.
#include <cstdint>
#include <string_view>

#include "core/error.hpp"
#include "fuzz_common.hpp"
#include "fuzz_seeds.hpp"
#include "motion/bvh.hpp"
#include "motion/clip_io.hpp"
#include "motion/deepmimic.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  mimic::Clip clip;
  try {
    clip = mimic::parse_clip(mimic::fuzz::as_text(data, size), "fuzz.mclip");
  } catch (const mimic::Error&) {
    return 0;
  }
  mimic::fuzz::require_valid(clip, data, size);  // what a reader accepts must be a valid clip
  return 0;
}

namespace {

// The first `frames` frames of a clip, written in the native format.
std::string clip_seed(mimic::Clip clip, std::size_t frames) {
  if (clip.frames.size() > frames) clip.frames.resize(frames);
  return mimic::write_clip(clip);
}

}  // namespace

std::vector<std::string> MimicFuzzSeeds() {
  std::vector<std::string> seeds;
  // Shared motions converted to the native format (a few frames each): a DeepMimic walk
  // (revolute joints, limits, torque limits) and a CMU BVH (end sites).
  const auto character = mimic::fuzz::shared_files({"deepmimic/characters/humanoid3d.txt"}, 1 << 20);
  const auto walk = mimic::fuzz::shared_files({"deepmimic/motions/humanoid3d_walk.txt"}, 1 << 20);
  if (character.size() == 1 && walk.size() == 1) {
    const mimic::Skeleton sk = mimic::parse_deepmimic_character(character[0], "humanoid3d.txt").skeleton;
    seeds.push_back(clip_seed(mimic::parse_deepmimic_motion(walk[0], "humanoid3d_walk.txt", sk), 4));
  }
  for (const std::string& bvh : mimic::fuzz::shared_files({"cmu-bvh/131_01.bvh"}, 1 << 21))
    seeds.push_back(clip_seed(mimic::parse_bvh(bvh, "131_01.bvh"), 3));
  // Built in: root, spherical spine, revolute elbow, a site; and a root-only clip without sites.
  seeds.push_back(
      "# mimic clip\nformat: mimic-clip\nversion: 1\nname: \"wave\"\nfps: 30\nloop: wrap\nframes: 2\njoints:\n"
      "  - {name: \"root\", parent: -1, type: free, offset: [0, 0, 0], rest: [1, 0, 0, 0]}\n"
      "  - {name: \"spine\", parent: 0, type: spherical, offset: [0, 0, 0.3], rest: [1, 0, 0, 0],"
      " limits: [[-1, 1], [-0.5, 0.5], [-0.25, 0.25]]}\n"
      "  - {name: \"elbow\", parent: 1, type: revolute, offset: [0.25, 0, 0.1], rest: [1, 0, 0, 0], axis: [0, 1, 0],"
      " limits: [[-2, 0]], torque_limit: 40, end_effector: true}\n"
      "sites:\n  - {name: \"hand\", joint: 2, offset: [0.2, 0, 0]}\n---\n"
      "0 0 1 1 0 0 0 1 0 0 0 1 0 0 0\n0.125 0 1 1 0 0 0 0.8 0.6 0 0 0.6 0 0.8 0\n");
  seeds.push_back("format: mimic-clip\nversion: 1\nfps: 60\nloop: none\nframes: 1\njoints:\n"
                  "  - {name: root, parent: -1, type: free}\n---\r\n0 0 0.9 1 0 0 0\r\n");
  return seeds;
}
