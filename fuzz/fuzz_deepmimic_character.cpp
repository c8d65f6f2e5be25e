// Fuzz target: DeepMimic character import. Any input must parse or raise mimic::Error, never crash.
#include <cstdint>
#include <string_view>

#include "core/error.hpp"
#include "fuzz_common.hpp"
#include "fuzz_seeds.hpp"
#include "motion/deepmimic.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    mimic::parse_deepmimic_character(mimic::fuzz::as_text(data, size), "fuzz_character.txt");
  } catch (const mimic::Error&) {
  }
  return 0;
}

std::vector<std::string> MimicFuzzSeeds() {
  auto seeds = mimic::fuzz::shared_files({"deepmimic/characters/humanoid3d.txt", "deepmimic/characters/dog3d.txt"}, 40000);
  // A root, a spherical, a revolute and a fixed joint, with bodies of every shape.
  seeds.push_back(
      "{\"Skeleton\": {\"Joints\": [\n"
      "{\"ID\": 0, \"Name\": \"root\", \"Type\": \"none\", \"Parent\": -1, \"AttachX\": 0, \"AttachY\": 0, \"AttachZ\": 0,"
      " \"AttachThetaX\": 0, \"AttachThetaY\": 0, \"AttachThetaZ\": 0},\n"
      "{\"ID\": 1, \"Name\": \"chest\", \"Type\": \"spherical\", \"Parent\": 0, \"AttachX\": 0, \"AttachY\": 0.2, \"AttachZ\": 0,"
      " \"AttachThetaX\": 0, \"AttachThetaY\": 0, \"AttachThetaZ\": 0, \"LimLow0\": -1, \"LimHigh0\": 1, \"LimLow1\": 1,"
      " \"LimHigh1\": 0, \"LimLow2\": -1, \"LimHigh2\": 1, \"TorqueLim\": 200},\n"
      "{\"ID\": 2, \"Name\": \"knee\", \"Type\": \"revolute\", \"Parent\": 0, \"AttachX\": 0, \"AttachY\": -0.4, \"AttachZ\": 0.08,"
      " \"AttachThetaX\": 0.1, \"AttachThetaY\": 0.2, \"AttachThetaZ\": 0.3, \"LimLow0\": -3, \"LimHigh0\": 0, \"TorqueLim\": 150},\n"
      "{\"ID\": 3, \"Name\": \"wrist\", \"Type\": \"fixed\", \"Parent\": 1, \"AttachX\": 0.3, \"AttachY\": 0, \"AttachZ\": 0,"
      " \"AttachThetaX\": 0, \"AttachThetaY\": 0, \"AttachThetaZ\": 0.5, \"IsEndEffector\": 1}\n"
      "]},\n\"BodyDefs\": [\n"
      "{\"Name\": \"root\", \"Shape\": \"sphere\", \"Mass\": 6, \"AttachX\": 0, \"AttachY\": 0, \"AttachZ\": 0, \"AttachThetaX\": 0,"
      " \"AttachThetaY\": 0, \"AttachThetaZ\": 0, \"Param0\": 0.2, \"Param1\": 0, \"Param2\": 0, \"ColGroup\": 1},\n"
      "{\"Name\": \"chest\", \"Shape\": \"box\", \"Mass\": 10, \"AttachX\": 0, \"AttachY\": 0.1, \"AttachZ\": 0, \"AttachThetaX\": 0,"
      " \"AttachThetaY\": 0, \"AttachThetaZ\": 0, \"Param0\": 0.2, \"Param1\": 0.3, \"Param2\": 0.1, \"EnableFallContact\": 1},\n"
      "{\"Name\": \"knee\", \"Shape\": \"capsule\", \"Mass\": 3, \"AttachX\": 0, \"AttachY\": -0.2, \"AttachZ\": 0, \"AttachThetaX\": 0,"
      " \"AttachThetaY\": 0, \"AttachThetaZ\": 0, \"Param0\": 0.09, \"Param1\": 0.31, \"Param2\": 0, \"ColorR\": 0.1},\n"
      "{\"Name\": \"wrist\", \"Shape\": \"cylinder\", \"Mass\": 1, \"AttachX\": 0.05, \"AttachY\": 0, \"AttachZ\": 0, \"AttachThetaX\": 0,"
      " \"AttachThetaY\": 0, \"AttachThetaZ\": 0, \"Param0\": 0.08, \"Param1\": 0.1, \"Param2\": 0}\n"
      "]}\n");
  // Root only, no bodies; YAML flow style rather than JSON.
  seeds.push_back("{Skeleton: {Joints: [{ID: 0, Name: root, Type: none, Parent: -1}]}}\n");
  return seeds;
}
