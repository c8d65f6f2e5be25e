#include "control/completion.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>

#include "control/skill_impl.hpp"
#include "core/error.hpp"
#include "env/character_env.hpp"
#include "env/context_env.hpp"
#include "env/imitation_env.hpp"

namespace mimic {

namespace {

constexpr double kFloorPad = 2e-3;  // metres left between the floor and a start raised out of it

bool same_joints(const Skeleton& a, const Skeleton& b) {
  if (a.joints.size() != b.joints.size()) return false;
  for (std::size_t j = 0; j < a.joints.size(); ++j)
    if (a.joints[j].name != b.joints[j].name || a.joints[j].parent != b.joints[j].parent) return false;
  return true;
}

// `p` moved rigidly to the origin facing +X (its height kept).
Pose placed(Pose p) {
  p.rot[0] = (heading_rotation(-heading_angle(p.rot[0])) * p.rot[0]).normalized();
  p.root_pos = Vec3(0, 0, p.root_pos.z());
  return p;
}

}  // namespace

MotionCompletion::MotionCompletion(std::vector<std::shared_ptr<const Skill>> skills) : skills_(std::move(skills)) {
  if (skills_.empty()) throw Error("motion completion needs at least one skill");
  for (const auto& s : skills_) {
    if (!s) throw Error("motion completion: a skill is null");
    const std::unique_ptr<Env> probe = make_skill_env(*s);
    const CharacterEnv* character = character_of(*probe);
    if (!character) throw Error("motion completion: skill '" + s->name() + "' (" + s->directory().string() + ") drives no character");
    const Skeleton& sk = character->world().character().skeleton;
    if (clips_.empty()) skeleton_ = sk;
    else if (!same_joints(sk, skeleton_))
      throw Error("motion completion: skill '" + s->name() + "' (" + s->directory().string() + ") acts on another character than skill '" +
                  skills_.front()->name() + "'");
    clips_.push_back(skill_clips(*s));
    if (clips_.back().empty())
      throw Error("motion completion: skill '" + s->name() + "' (" + s->directory().string() +
                  ") starts from no clip (its env.init is not mocap), so it has no frames to match a pose with");
    std::vector<const Clip*> raw;
    for (const auto& c : clips_.back()) {
      if (!same_joints(c->skeleton, skeleton_))
        throw Error("motion completion: skill '" + s->name() + "': its clip '" + c->name + "' is not on its character's skeleton");
      raw.push_back(c.get());
    }
    matchers_.emplace_back(raw, MatchHeights::RootRelative);  // a still shows no floor
  }
}

std::vector<CompletionMatch> MotionCompletion::match(const Pose& pose) const {
  std::vector<CompletionMatch> out;
  for (std::size_t i = 0; i < skills_.size(); ++i) {
    const FrameMatch f = matchers_[i].nearest(pose);
    const Clip& clip = *clips_[i][static_cast<std::size_t>(f.clip)];
    out.push_back({i, clip.name, f.frame, f.frame / clip.fps, f.distance});
  }
  std::stable_sort(out.begin(), out.end(), [](const CompletionMatch& a, const CompletionMatch& b) { return a.distance < b.distance; });
  return out;
}

void MotionCompletion::start(Controller& controller, const Pose& pose, const CompletionMatch& match, StartAt at) const {
  if (match.skill >= skills_.size()) throw Error("motion completion: no skill " + std::to_string(match.skill));
  if (pose.rot.size() != skeleton_.joints.size())
    throw Error("motion completion: a pose of " + std::to_string(pose.rot.size()) + " joints for a character of " + std::to_string(skeleton_.joints.size()));
  const Skill& skill = *skills_[match.skill];
  const auto clip = std::find_if(clips_[match.skill].begin(), clips_[match.skill].end(), [&](const auto& c) { return c->name == match.clip; });
  if (clip == clips_[match.skill].end()) throw Error("motion completion: skill '" + skill.name() + "' has no clip '" + match.clip + "'");
  const std::unique_ptr<Env> probe = make_skill_env(skill);
  CharacterEnv& env = *character_of(*probe);
  // The frame's state, and the pose, each at the origin facing +X.
  InitState s = place_at_track_start(env.state_on_clip(**clip, match.time));
  if (at == StartAt::Pose) {
    const Pose still = placed(pose);
    // The past: the clip's, each joint turned by the frame-to-pose difference.
    std::vector<Quat> change(still.rot.size());
    for (std::size_t j = 0; j < still.rot.size(); ++j) change[j] = (s.pose.rot[j].conjugate() * still.rot[j]).normalized();
    for (Pose& p : s.past) {
      p.root_pos += still.root_pos - s.pose.root_pos;
      for (std::size_t j = 0; j < p.rot.size(); ++j) p.rot[j] = (p.rot[j] * change[j]).normalized();
    }
    s.pose = still;
  }
  // Out of the floor: every pose raised by the depth the pose's bodies reach into it.
  World& world = env.world();
  world.set_state(s.pose);
  const double depth = world.ground_penetration();
  const double lift = depth > 0 ? depth + kFloorPad : 0.0;
  s.pose.root_pos.z() += lift;
  for (Pose& p : s.past) p.root_pos.z() += lift;
  // In MuJoCo's terms, through the skill's world.
  const mjModel* m = probe->physics_model();
  const mjData* d = probe->physics_data();
  auto qpos = [&] { return Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(d->qpos, m->nq)); };
  std::vector<Eigen::VectorXd> past;
  for (const Pose& p : s.past) world.set_state(p), past.push_back(qpos());
  world.set_state(s.pose, &s.velocity);
  const Eigen::VectorXd now = qpos(), velocity = Eigen::Map<const Eigen::VectorXd>(d->qvel, m->nv);
  controller.start(skill.name(), now, velocity, past, match.time);
}

}  // namespace mimic
