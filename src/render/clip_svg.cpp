#include "render/clip_svg.hpp"

#include <algorithm>
#include <cstdio>

#include <fmt/format.h>
#include <limits>

#include "core/error.hpp"
#include "motion/kinematics.hpp"
#include "motion/mirror.hpp"

namespace mimic {

std::string svg_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    else if (c == '\'') out += "&apos;";
    else out += c;
  }
  return out;
}

namespace {

// Lines from each joint to its parent and to its sites, projected by `proj`.
// Joints on the character's left: of each mirror pair, the one on the +Y side at rest.
std::vector<bool> left_side(const Skeleton& sk) {
  std::vector<bool> left(sk.joints.size(), false);
  try {
    const std::vector<int> twin = mirror_map(sk);
    const LinkFrames rest = forward_kinematics(sk, rest_pose(sk));
    for (std::size_t j = 0; j < sk.joints.size(); ++j)
      left[j] = twin[j] != static_cast<int>(j) && rest.joint_pos[j].y() > rest.joint_pos[static_cast<std::size_t>(twin[j])].y();
  } catch (const Error&) {
    // No consistent left/right pairs: one colour.
  }
  return left;
}

template <class Proj>
std::string stick_figure(const Skeleton& sk, const std::vector<bool>& left, const LinkFrames& fk, Proj proj) {
  std::string s;
  auto line = [&](const Vec3& a, const Vec3& b, const char* colour) {
    const auto [x1, y1] = proj(a);
    const auto [x2, y2] = proj(b);
    s += fmt::format("<line x1='{:.1f}' y1='{:.1f}' x2='{:.1f}' y2='{:.1f}' ", x1, y1, x2, y2);
    s += std::string("stroke='") + colour + "' stroke-width='3' stroke-linecap='round'/>\n";
  };
  for (std::size_t j = 1; j < sk.joints.size(); ++j)
    line(fk.joint_pos[static_cast<std::size_t>(sk.joints[j].parent)], fk.joint_pos[j], left[j] ? "#d9534f" : "#2c6fbb");
  for (std::size_t i = 0; i < sk.sites.size(); ++i) line(fk.joint_pos[static_cast<std::size_t>(sk.sites[i].joint)], fk.site_pos[i], "#777");
  return s;
}

}  // namespace

std::string clip_picture_svg(const Clip& clip, const ClipPictureOptions& opts) {
  const int panels = std::max(1, std::min(opts.panels, clip.num_frames()));
  const std::vector<bool> is_left = left_side(clip.skeleton);
  // Each panel is drawn in its frame's heading frame: side view = facing right.
  std::vector<LinkFrames> fks;
  std::vector<HeadingFrame> headings;
  for (int k = 0; k < panels; ++k) {
    const int f = panels == 1 ? 0 : static_cast<int>(std::lround(static_cast<double>(k) * (clip.num_frames() - 1) / (panels - 1)));
    const Pose& pose = clip.frames[static_cast<std::size_t>(f)];
    fks.push_back(forward_kinematics(clip.skeleton, pose));
    headings.push_back(HeadingFrame::of(pose));
  }
  // Common scale: the tallest extent of any panel fits the panel height.
  double zmax = 0.0, half_width = 0.0;
  for (std::size_t k = 0; k < fks.size(); ++k) {
    const LinkFrames& fk = fks[k];
    const HeadingFrame& h = headings[k];
    for (const auto* pts : {&fk.joint_pos, &fk.site_pos}) {
      for (const Vec3& p : *pts) {
        zmax = std::max(zmax, p.z());
        const Vec3 l = h.to_local(p);
        half_width = std::max({half_width, std::abs(l.x()), std::abs(l.y())});
      }
    }
  }
  const double ph = opts.panel_px, margin = 20.0;
  const double scale = (ph - 2 * margin) / std::max(zmax, 1e-3);
  const double pw = std::max(2 * half_width * scale + 2 * margin, 0.6 * ph);
  const double width = pw * panels, plot_h = 160.0, height = 2 * ph + plot_h + 60;
  std::string svg = fmt::format("<svg xmlns='http://www.w3.org/2000/svg' width='{:.0f}' height='{:.0f}' viewBox='0 0 {:.0f} {:.0f}'>\n", width, height, width, height);
  svg += "<rect width='100%' height='100%' fill='white'/>\n<style>text{font-family:sans-serif;font-size:12px;fill:#333}</style>\n";
  char title[400];
  std::snprintf(title, sizeof title, "%s: %d frames at %.2f Hz, %.2f s, loop %s, %d joints (%d DoF)", clip.name.c_str(),
                clip.num_frames(), clip.fps, clip.duration(), to_string(clip.loop), clip.skeleton.num_joints(), clip.skeleton.dof_count());
  svg += "<text x='8' y='16'>" + svg_escape(title) + "</text>\n";
  for (int k = 0; k < panels; ++k) {
    const LinkFrames& fk = fks[static_cast<std::size_t>(k)];
    const HeadingFrame& hf = headings[static_cast<std::size_t>(k)];
    const double cx = pw * (k + 0.5);
    for (int view = 0; view < 2; ++view) {  // 0: side (x right), 1: front (y right)
      const double base = 24 + ph * (view + 1) - margin;
      svg += fmt::format("<line x1='{:.1f}' y1='{:.1f}' x2='{:.1f}' y2='{:.1f}' stroke='#bbb'/>\n", cx - pw / 2 + 4, base, cx + pw / 2 - 4, base);
      auto proj = [&](const Vec3& p) {
        const Vec3 l = hf.to_local(p);
        const double h = view == 0 ? l.x() : l.y();  // front view: the character's left on our right
        return std::pair<double, double>{cx + h * scale, base - l.z() * scale};
      };
      svg += stick_figure(clip.skeleton, is_left, fk, proj);
    }
  }
  svg += fmt::format("<text x='8' y='{:.0f}'>side view (facing right) above, front view below; {} frames evenly spaced</text>\n",
             2 * ph + 36, panels, 0.0, 0.0);
  // Heights over time.
  const double top = 2 * ph + 50, left = 50, right = width - 20;
  std::vector<double> root_z, low_z;
  double zhi = 0.0;
  LinkFrames fk;
  for (const Pose& p : clip.frames) {
    forward_kinematics(clip.skeleton, p, fk);
    double lo = std::numeric_limits<double>::infinity();
    for (const Vec3& x : fk.joint_pos) lo = std::min(lo, x.z());
    for (const Vec3& x : fk.site_pos) lo = std::min(lo, x.z());
    root_z.push_back(p.root_pos.z());
    low_z.push_back(lo);
    zhi = std::max(zhi, p.root_pos.z());
  }
  const double zlo = std::min(0.0, *std::min_element(low_z.begin(), low_z.end()));
  auto px = [&](std::size_t i) { return left + (right - left) * static_cast<double>(i) / static_cast<double>(std::max<std::size_t>(1, root_z.size() - 1)); };
  auto py = [&](double z) { return top + plot_h - 20 - (z - zlo) / std::max(zhi - zlo, 1e-6) * (plot_h - 30); };
  svg += fmt::format("<line x1='{:.1f}' y1='{:.1f}' x2='{:.1f}' y2='{:.1f}' stroke='#999'/>\n", left, py(0), right, py(0));
  for (const auto& [series, colour] : {std::pair{&root_z, "#2c6fbb"}, std::pair{&low_z, "#5cb85c"}}) {
    std::string pts;
    for (std::size_t i = 0; i < series->size(); ++i) {
      char b[48];
      std::snprintf(b, sizeof b, "%.1f,%.1f ", px(i), py((*series)[i]));
      pts += b;
    }
    svg += std::string("<polyline fill='none' stroke='") + colour + "' stroke-width='1.5' points='" + pts + "'/>\n";
  }
  svg += fmt::format("<text x='{:.0f}' y='{:.0f}'>height over time (m): root (blue), lowest joint or site (green); 0 to {:.2f} m over {:.2f} s</text>\n",
             left, top + plot_h - 2, zhi, clip.duration());
  svg += "</svg>\n";
  return svg;
}

}  // namespace mimic
