// Fuzz target: retarget maps (YAML). Any input must parse or raise mimic::Error, never crash; a
// map that parses retargets the built-in jumping jack onto its own skeleton into a valid clip or
// raises mimic::Error.
#include <cstdint>
#include <string_view>

#include "core/error.hpp"
#include "fuzz_common.hpp"
#include "fuzz_seeds.hpp"
#include "motion/builtin.hpp"
#include "motion/retarget.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const mimic::Clip jack = [] {
    mimic::Clip c = mimic::builtin_jumping_jack();
    c.frames.resize(3);
    return c;
  }();
  mimic::Clip out;
  try {
    const mimic::RetargetMap map = mimic::parse_retarget_map(mimic::fuzz::as_text(data, size), "fuzz.yaml");
    out = mimic::retarget(jack, jack.skeleton, map);
  } catch (const mimic::Error&) {
    return 0;
  }
  mimic::fuzz::require_valid(out, data, size);  // what a reader accepts must be a valid clip
  return 0;
}

std::vector<std::string> MimicFuzzSeeds() {
  std::vector<std::string> seeds;
  const std::filesystem::path file = std::filesystem::path(MIMIC_SOURCE_DIR) / "data" / "retarget" / "cmu_to_humanoid3d.yaml";
  try {
    seeds.push_back(mimic::read_text_file(file));
  } catch (const mimic::Error&) {
  }
  seeds.push_back(
      "joints: {root: root, chest: chest, left_hip: left_hip, left_knee: left_knee, right_elbow: right_elbow}\n"
      "scale: auto\nsites:\n  - {name: toe, joint: left_ankle, offset: [0.1, 0, -0.05]}\nground_fix: true\n"
      "end_effectors: [left_ankle, toe]\n");
  seeds.push_back("joints:\n  root: root\nscale: 0.5\nground_fix: false\n");
  return seeds;
}
