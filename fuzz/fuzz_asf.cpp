// Fuzz target: Acclaim ASF import. Any input must parse or raise mimic::Error, never crash.
#include <cstdint>
#include <string_view>

#include "core/error.hpp"
#include "fuzz_common.hpp"
#include "fuzz_seeds.hpp"
#include "motion/asf_amc.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    mimic::parse_asf(mimic::fuzz::as_text(data, size), "fuzz.asf");
  } catch (const mimic::Error&) {
  }
  return 0;
}

std::vector<std::string> MimicFuzzSeeds() {
  auto seeds = mimic::fuzz::shared_files({"cmu-asf/07.asf"}, 40000);
  seeds.push_back(
      "# CMU style\n:version 1.10\n:name VICON\n:units\n  mass 1.0\n  length 0.45\n  angle deg\n"
      ":documentation\n   free text: with colons\n:root\n   order TX TY TZ RX RY RZ\n   axis XYZ\n"
      "   position 0 0 0\n   orientation 0 0 0\n:bonedata\n"
      "  begin\n     id 1\n     name lhipjoint\n     direction 0.692024 -0.648617 0.316857\n     length 2.40167\n"
      "     axis 0 0 -20 XYZ\n  end\n"
      "  begin\n     id 2\n     name lfemur\n     direction 0.34202 -0.939693 0\n     length 7.07479\n"
      "     axis 0 0 20 XYZ\n    dof rx ry rz\n    limits (-160.0 , 20.0)\n           (-70.0 , 70.0)\n"
      "           (-60.0 , 70.0)\n  end\n"
      "  begin\n     id 3\n     name ltibia\n     direction 0.34202 -0.939693 0\n     length 7.43669\n"
      "     axis 0 0 20 XYZ\n    dof rx\n    limits (-10.0 , 170.0)\n  end\n"
      "  begin\n     id 4\n     name lfoot\n     direction 0 0 1\n     length 2.5\n"
      "     axis -90 7.1 20 XZY\n    dof rx rz\n    limits (-45.0 , 90.0)\n           (-inf inf)\n  end\n"
      ":hierarchy\n  begin\n    root lhipjoint\n    lhipjoint lfemur\n    lfemur ltibia\n    ltibia lfoot\n  end\n");
  seeds.push_back(
      ":units\n  angle rad\n:root\n order RX RY RZ TX TY TZ\n axis ZYX\n orientation 0.1 0.2 0.3\n:bonedata\n"
      "begin\n name a\n direction 0 1 0\n length 1\n axis 0.5 0 0 ZXY\n dof rz ry\n end\n"
      "begin\n name b\n direction 1 1 1\n length 0\n axis 0 0 0 XYZ\n end\n"
      ":hierarchy\nbegin\nroot a\na b\nend\n");
  return seeds;
}
