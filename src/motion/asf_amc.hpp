#pragma once
// Acclaim ASF (skeleton) and AMC (motion), the CMU motion-capture database's own formats.
// Each ASF bone becomes a joint at the bone's start (its parent's end); a bone with 3 rotational
// DoFs is spherical, 2 spherical (the missing axis stays at zero), 1 revolute, 0 fixed. Leaf
// bones get a site "<bone>_end" at their tip. AMC angles are applied as C * M * C^-1 with C the
// bone's "axis" rotation, M the product of the DoF rotations in listed order (Acclaim's rule).
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "motion/axes.hpp"
#include "motion/clip.hpp"

namespace mimic {

struct AsfSkeleton {
  Skeleton skeleton;  // mimic axes, metres
  // Per joint, the AMC channels in file order: "tx".."tz", "rx".."rz" (lower case).
  std::vector<std::vector<std::string>> dofs;
  std::vector<Quat> axis_rot;  // Acclaim's C per joint, in mimic axes
  bool degrees = true;         // ":units angle deg|rad"
  double metres_per_unit = 0.0;
  Quat basis = Quat::Identity();  // source axes -> mimic axes
  std::string source;
};

// Default axes for CMU data: Y up, facing +Z; scale 0 = from ":units length" (inches / length).
AxisConvention asf_default_axes();

AsfSkeleton parse_asf(std::string_view text, const std::string& source, const AxisConvention& axes = asf_default_axes());
AsfSkeleton load_asf(const std::filesystem::path& path, const AxisConvention& axes = asf_default_axes());

// `fps`: AMC files do not store their rate; CMU's is 120 Hz.
Clip parse_amc(std::string_view text, const std::string& source, const AsfSkeleton& asf, double fps = 120.0);
Clip load_amc(const std::filesystem::path& path, const AsfSkeleton& asf, double fps = 120.0);

// The ASF beside an AMC file by CMU's naming ("07_01.amc" -> "07.asf"), else the only .asf in
// the directory; empty if none.
std::filesystem::path guess_asf(const std::filesystem::path& amc_path);

}  // namespace mimic
