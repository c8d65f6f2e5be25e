// Fuzz target: Acclaim AMC import against a fixed built-in ASF. Any input must parse or raise
// mimic::Error, never crash.
#include <cstdint>
#include <string_view>

#include "core/error.hpp"
#include "fuzz_common.hpp"
#include "fuzz_seeds.hpp"
#include "motion/asf_amc.hpp"

namespace {

const char* const kAsf =
    ":units\n  length 0.45\n  angle deg\n:root\n   order TX TY TZ RX RY RZ\n   axis XYZ\n"
    "   position 0 0 0\n   orientation 0 0 0\n:bonedata\n"
    "  begin\n     name lhip\n     direction 1 0 0\n     length 2\n     axis 0 0 0 XYZ\n  end\n"
    "  begin\n     name lfemur\n     direction 0 -1 0\n     length 9\n     axis 0 0 20 XYZ\n     dof rx ry rz\n  end\n"
    "  begin\n     name ltibia\n     direction 0 -1 0\n     length 9\n     axis 0 0 20 XYZ\n     dof rx\n  end\n"
    "  begin\n     name lfoot\n     direction 0 0 1\n     length 3\n     axis -90 0 20 XYZ\n     dof rx rz\n  end\n"
    ":hierarchy\n  begin\n    root lhip\n    lhip lfemur\n    lfemur ltibia\n    ltibia lfoot\n  end\n";

const mimic::AsfSkeleton& skeleton() {
  static const mimic::AsfSkeleton asf = mimic::parse_asf(kAsf, "fuzz.asf");
  return asf;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const mimic::AsfSkeleton& asf = skeleton();
  mimic::Clip clip;
  try {
    clip = mimic::parse_amc(mimic::fuzz::as_text(data, size), "fuzz.amc", asf);
  } catch (const mimic::Error&) {
    return 0;
  }
  mimic::fuzz::require_valid(clip, data, size);  // what a reader accepts must be a valid clip
  return 0;
}

std::vector<std::string> MimicFuzzSeeds() {
  std::vector<std::string> seeds;
  seeds.push_back(
      "#!OML:ASF F:\\VICON\\USERDATA\\INST\\Cmu\\07.asf\n#!USER\n:FULLY-SPECIFIED\n:DEGREES\n"
      "1\nroot 9.37 17.8 -17.3 -3.3 -5.5 -86\nlfemur -20.1 4.3 -12\nltibia 37.5\nlfoot -9.9 3.2\n"
      "2\nroot 9.41 17.8 -17.2 -3.2 -5.4 -86.1\nlfemur -20.3 4.3 -11.9\nltibia 37.8\nlfoot -10 3.1\n"
      "3\nroot 9.45 17.9 -17.1 -3.1 -5.3 -86.2\nlhip\nlfoot -10.1 3\nltibia 38\nlfemur -20.5 4.2 -11.8\n");
  seeds.push_back(":RADIANS\n1\nroot 0 0 0 0.1 0.2 0.3\nlfemur 0 0 0\nltibia 1.5\nlfoot 0 0\n");
  return seeds;
}
