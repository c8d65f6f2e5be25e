#pragma once
// BVH (Biovision hierarchy) import: any channel order, any rotation order, any up/forward axes
// and unit scale. Joints with 3 rotation channels become spherical, 1 revolute, 0 fixed; end
// sites become sites named "<joint>_end".
#include <filesystem>
#include <string_view>

#include "motion/axes.hpp"
#include "motion/clip.hpp"

namespace mimic {

// Parses BVH text; `source` names it in errors. Throws ParseError on malformed input.
Clip parse_bvh(std::string_view text, const std::string& source, const AxisConvention& axes = {});
Clip load_bvh(const std::filesystem::path& path, const AxisConvention& axes = {});

}  // namespace mimic
