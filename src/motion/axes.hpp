#pragma once
// Conversion of a source file's axes and units into mimic's (Z up, X forward, Y left, metres).
#include <string>
#include <string_view>

#include "core/math.hpp"

namespace mimic {

struct AxisConvention {
  std::string up = "y";        // source axis pointing up: x, y, z, optionally signed ("-z")
  std::string forward = "z";   // source axis the character faces at rest
  double scale = 0.01;         // metres per source length unit
};

// Rotation taking source coordinates to mimic's: forward -> +X, up -> +Z, up x forward -> +Y.
// Throws Error if an axis name is invalid or the two axes are not perpendicular.
Quat source_to_mimic(const AxisConvention& conv);

// Signed unit axis from "x", "+y", "-z" (either case); throws Error otherwise.
Vec3 signed_axis(std::string_view name);

}  // namespace mimic
