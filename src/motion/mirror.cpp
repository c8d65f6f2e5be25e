#include "motion/mirror.hpp"

#include <array>

#include "core/error.hpp"

namespace mimic {
namespace {

// Names `name` could have on the other side.
std::vector<std::string> twin_names(const std::string& name) {
  static const std::array<std::pair<const char*, const char*>, 3> words = {
      {{"left", "right"}, {"Left", "Right"}, {"LEFT", "RIGHT"}}};
  std::vector<std::string> out;
  for (const auto& [l, r] : words) {
    for (const auto& [from, to] : {std::pair{l, r}, std::pair{r, l}}) {
      const std::string f(from);
      if (const auto pos = name.find(f); pos != std::string::npos) {
        std::string n = name;
        n.replace(pos, f.size(), to);
        out.push_back(n);
      }
    }
  }
  if (name.size() > 1) {
    const char c = name.front();
    const char swapped = c == 'l' ? 'r' : c == 'r' ? 'l' : c == 'L' ? 'R' : c == 'R' ? 'L' : '\0';
    if (swapped) out.push_back(swapped + name.substr(1));
  }
  if (name.size() > 2) {
    const std::string tail = name.substr(name.size() - 2);
    for (const auto& [a, b] : {std::pair{"_l", "_r"}, std::pair{"_L", "_R"}, std::pair{".L", ".R"}}) {
      if (tail == a) out.push_back(name.substr(0, name.size() - 2) + b);
      if (tail == b) out.push_back(name.substr(0, name.size() - 2) + a);
    }
  }
  return out;
}

// Reflection through the X-Z plane: S R S for a rotation, (x, -y, z) for a point.
Quat reflect(const Quat& q) { return Quat(q.w(), -q.x(), q.y(), -q.z()); }
Vec3 reflect(const Vec3& v) { return Vec3(v.x(), -v.y(), v.z()); }

}  // namespace

std::vector<int> mirror_map(const Skeleton& sk) {
  const int n = sk.num_joints();
  std::vector<int> twin(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    twin[static_cast<std::size_t>(i)] = i;
    for (const std::string& cand : twin_names(sk.joints[static_cast<std::size_t>(i)].name)) {
      const int j = sk.find(cand);
      if (j >= 0 && j != i) {
        twin[static_cast<std::size_t>(i)] = j;
        break;
      }
    }
  }
  for (int i = 0; i < n; ++i) {
    const int j = twin[static_cast<std::size_t>(i)];
    if (twin[static_cast<std::size_t>(j)] != i)
      throw Error("mirror: joints '" + sk.joints[static_cast<std::size_t>(i)].name + "' and '" +
                  sk.joints[static_cast<std::size_t>(j)].name + "' do not pair up both ways");
    const int pi = sk.joints[static_cast<std::size_t>(i)].parent, pj = sk.joints[static_cast<std::size_t>(j)].parent;
    if (i > 0 && twin[static_cast<std::size_t>(pi)] != pj)
      throw Error("mirror: twins '" + sk.joints[static_cast<std::size_t>(i)].name + "' and '" +
                  sk.joints[static_cast<std::size_t>(j)].name + "' have parents that are not twins");
  }
  return twin;
}

Clip mirror(const Clip& clip) { return mirror(clip, mirror_map(clip.skeleton)); }

Clip mirror(const Clip& clip, const std::vector<int>& twin) {
  const Skeleton& sk = clip.skeleton;
  if (twin.size() != sk.joints.size()) throw Error("mirror: twin map does not match the skeleton");
  Clip out = clip;
  out.name = clip.name + "_mirrored";
  for (std::size_t f = 0; f < clip.frames.size(); ++f) {
    const Pose& p = clip.frames[f];
    Pose& m = out.frames[f];
    m.root_pos = reflect(p.root_pos);
    m.rot[0] = reflect(p.rot[0]);
    for (std::size_t j = 1; j < sk.joints.size(); ++j) {
      const auto t = static_cast<std::size_t>(twin[j]);
      // F'_j = S F_t S  =>  q'_j = rest_j^-1 (S rest_t S) (S q_t S); exact inverse of itself.
      m.rot[j] = canonical((sk.joints[j].rest.conjugate() * reflect(sk.joints[t].rest) * reflect(p.rot[t])).normalized());
    }
  }
  return out;
}

}  // namespace mimic
