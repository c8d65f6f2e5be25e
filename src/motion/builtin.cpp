#include "motion/builtin.hpp"

#include "motion/kinematics.hpp"
#include "motion/resample.hpp"

namespace mimic {
namespace {

Joint make_joint(const char* name, int parent, JointType type, const Vec3& offset, const Vec3& axis = Vec3::UnitZ()) {
  Joint j;
  j.name = name;
  j.parent = parent;
  j.type = type;
  j.offset = offset;
  j.axis = axis;
  return j;
}

}  // namespace

Skeleton builtin_humanoid() {
  Skeleton sk;
  using T = JointType;
  auto add = [&](const char* name, const char* parent, T type, Vec3 offset, Vec3 axis = Vec3::UnitZ()) {
    sk.joints.push_back(make_joint(name, parent ? sk.find(parent) : -1, type, offset, axis));
  };
  add("root", nullptr, T::Free, Vec3::Zero());
  add("chest", "root", T::Spherical, Vec3(0, 0, 0.25));
  add("neck", "chest", T::Spherical, Vec3(0, 0, 0.24));
  for (const char* side : {"right", "left"}) {
    const double s = side[0] == 'r' ? -1.0 : 1.0;
    const std::string p(side);
    add((p + "_hip").c_str(), "root", T::Spherical, Vec3(0, s * 0.09, 0));
    add((p + "_knee").c_str(), (p + "_hip").c_str(), T::Revolute, Vec3(0, 0, -0.44), Vec3(0, -1, 0));
    add((p + "_ankle").c_str(), (p + "_knee").c_str(), T::Spherical, Vec3(0, 0, -0.42));
    add((p + "_shoulder").c_str(), "chest", T::Spherical, Vec3(-0.02, s * 0.19, 0.24));
    add((p + "_elbow").c_str(), (p + "_shoulder").c_str(), T::Revolute, Vec3(0, 0, -0.28), Vec3(0, -1, 0));
    add((p + "_wrist").c_str(), (p + "_elbow").c_str(), T::Fixed, Vec3(0, 0, -0.26));
  }
  sk.sites.push_back(Site{"head_top", sk.find("neck"), Vec3(0, 0, 0.28)});
  sk.sites.push_back(Site{"right_sole", sk.find("right_ankle"), Vec3(0.04, 0, -0.06)});
  sk.sites.push_back(Site{"left_sole", sk.find("left_ankle"), Vec3(0.04, 0, -0.06)});
  return sk;
}

Clip builtin_jumping_jack() {
  Clip keys;
  keys.name = "jumping_jack";
  keys.skeleton = builtin_humanoid();
  keys.loop = LoopMode::Wrap;
  keys.fps = 1.0 / 0.3;  // keyframes every 0.3 s: together, apart (airborne), together, ...
  const Skeleton& sk = keys.skeleton;
  auto pose = [&](double spread, double arms, double height, double knee) {
    Pose p = rest_pose(sk, Vec3(0, 0, height));
    for (const char* side : {"right", "left"}) {
      const double s = side[0] == 'r' ? -1.0 : 1.0;  // abduction: the right limb turns about -x
      const std::string n(side);
      p.rot[static_cast<std::size_t>(sk.find(n + "_hip"))] = axis_rotation('x', s * spread);
      p.rot[static_cast<std::size_t>(sk.find(n + "_ankle"))] = axis_rotation('x', -s * spread);
      p.rot[static_cast<std::size_t>(sk.find(n + "_knee"))] = axis_rotation('y', knee);
      p.rot[static_cast<std::size_t>(sk.find(n + "_shoulder"))] = axis_rotation('x', s * arms);
      p.rot[static_cast<std::size_t>(sk.find(n + "_elbow"))] = axis_rotation('y', -0.1);
    }
    return p;
  };
  // Standing height: hip 0.86 m above the ankle joints plus 6 cm to the sole.
  keys.frames = {pose(0.0, 0.15, 0.92, 0.05), pose(0.30, 2.6, 0.97, 0.0), pose(0.32, 2.8, 0.90, 0.25),
                 pose(0.0, 0.15, 0.92, 0.05)};
  Clip clip = resample(keys, 30.0);
  const double lift = -clip_min_height(clip);  // soles on the floor at the lowest point
  for (Pose& p : clip.frames) p.root_pos.z() += lift;
  return clip;
}

Clip builtin_squat() {
  Clip keys;
  keys.name = "squat";
  keys.skeleton = builtin_humanoid();
  keys.loop = LoopMode::Wrap;
  keys.fps = 1.0;  // keyframes every second: standing, squatting with the arms forward, standing
  const Skeleton& sk = keys.skeleton;
  // `hip` flexes the thighs forward, `knee` bends the knees, the ankles keep the feet flat; the
  // chest leans forward by `lean` and the arms rise forward by `arms`. Flexion is about -y for
  // the hips, shoulders and chest (the limbs hang along -z) and +y for the knees and elbows.
  auto pose = [&](double hip, double knee, double lean, double arms) {
    Pose p = rest_pose(sk, Vec3::Zero());
    p.rot[static_cast<std::size_t>(sk.find("chest"))] = axis_rotation('y', lean);
    for (const char* side : {"right", "left"}) {
      const std::string n(side);
      p.rot[static_cast<std::size_t>(sk.find(n + "_hip"))] = axis_rotation('y', -hip);
      p.rot[static_cast<std::size_t>(sk.find(n + "_knee"))] = axis_rotation('y', knee);
      p.rot[static_cast<std::size_t>(sk.find(n + "_ankle"))] = axis_rotation('y', hip - knee);
      p.rot[static_cast<std::size_t>(sk.find(n + "_shoulder"))] = axis_rotation('y', -arms);
      p.rot[static_cast<std::size_t>(sk.find(n + "_elbow"))] = axis_rotation('y', -0.1);
    }
    return p;
  };
  keys.frames = {pose(0.05, 0.1, 0.0, 0.2), pose(0.6, 1.0, 0.25, 1.3), pose(0.05, 0.1, 0.0, 0.2)};
  Clip clip = resample(keys, 30.0);
  // Every frame with its soles on the floor: the feet stay planted while the hips go down.
  for (Pose& p : clip.frames) {
    Clip one;
    one.skeleton = clip.skeleton;
    one.frames = {p};
    one.fps = clip.fps;
    p.root_pos.z() -= clip_min_height(one);
  }
  return clip;
}

}  // namespace mimic
