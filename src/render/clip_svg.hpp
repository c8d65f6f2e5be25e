#pragma once
// A picture of a clip without any GL: an SVG filmstrip of stick figures (side and front views)
// and a plot of the root's and the lowest point's height over time.
#include <string>

#include "motion/clip.hpp"

namespace mimic {

struct ClipPictureOptions {
  int panels = 8;        // frames shown, evenly spaced over the clip
  double panel_px = 180;  // height of one panel
};

std::string clip_picture_svg(const Clip& clip, const ClipPictureOptions& opts = {});

// Text made safe inside SVG elements and single-quoted attributes (< > & ').
std::string svg_escape(const std::string& s);

}  // namespace mimic
