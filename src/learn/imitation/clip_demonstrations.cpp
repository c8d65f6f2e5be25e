#include "learn/imitation/clip_demonstrations.hpp"

#include <mujoco/mujoco.h>

#include "core/error.hpp"

namespace mimic {

Demonstrations clip_demonstrations(CharacterEnv& env, const Clip& clip, int passes) {
  if (passes < 1) throw Error("clip demonstrations: passes must be >= 1");
  if (clip.skeleton.num_joints() != static_cast<int>(env.world().pose().rot.size()))
    throw Error("clip '" + clip.name + "' does not fit the environment's character (" + std::to_string(clip.skeleton.num_joints()) +
                " joints, the character " + std::to_string(env.world().pose().rot.size()) + ")");
  const double dt = env.physics_model()->opt.timestep * env.world().substeps();
  const int steps = static_cast<int>(std::floor(clip.duration() / dt));  // transitions per pass
  if (steps < 1) throw Error("clip '" + clip.name + "' is shorter than one control step");
  Demonstrations d;
  d.source = "clip " + clip.name;
  d.layout = env.observation_layout();
  const auto n = static_cast<Eigen::Index>(steps) * passes;
  d.obs.resize(n, env.observation_size());
  d.next_obs.resize(n, env.observation_size());
  d.action.resize(n, 0);
  Eigen::Index row = 0;
  for (int p = 0; p < passes; ++p) {
    const double start = dt * p / passes;
    for (int k = 0; k < steps && start + (k + 1) * dt <= clip.duration(); ++k, ++row) {
      d.obs.row(row) = env.reset(env.state_on_clip(clip, start + k * dt)).transpose();
      d.next_obs.row(row) = env.reset(env.state_on_clip(clip, start + (k + 1) * dt)).transpose();
      d.episode.push_back(p);
    }
  }
  d.obs.conservativeResize(row, Eigen::NoChange);
  d.next_obs.conservativeResize(row, Eigen::NoChange);
  d.action.conservativeResize(row, Eigen::NoChange);
  return d;
}

Demonstrations clip_demonstrations(CharacterEnv& env, const std::vector<Clip>& clips, int passes) {
  if (clips.empty()) throw Error("clip demonstrations: no clip given");
  Demonstrations d;
  for (const Clip& clip : clips) d.append(clip_demonstrations(env, clip, passes));
  return d;
}

}  // namespace mimic
