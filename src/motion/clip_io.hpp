#pragma once
// mimic's own clip format (".mclip", documented in docs/clip-format.md) and loading of any
// supported motion file by its extension.
#include <filesystem>
#include <string>
#include <string_view>

#include "motion/axes.hpp"
#include "motion/clip.hpp"

namespace mimic {

std::string write_clip(const Clip& clip);
Clip parse_clip(std::string_view text, const std::string& source);
void save_clip(const Clip& clip, const std::filesystem::path& path);  // atomic

// What load_motion needs besides the file itself.
struct LoadOptions {
  std::filesystem::path character;  // DeepMimic character for .txt motions (guessed if empty)
  std::filesystem::path asf;        // skeleton for .amc motions (guessed if empty)
  AxisConvention axes;              // BVH axes and units
  double amc_fps = 120.0;           // AMC files do not store their rate
};

// Loads .mclip, .bvh, .amc (with its .asf) or DeepMimic .txt (with its character file).
// Throws Error/ParseError naming the file on any problem.
Clip load_motion(const std::filesystem::path& path, const LoadOptions& opts = {});

}  // namespace mimic
