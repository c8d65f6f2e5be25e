#pragma once
// Helpers of the imitation environment's tests (imitation_env*_test.cpp).
#include <algorithm>
#include <memory>
#include <stdexcept>
#include <string>

#include "core/error.hpp"
#include "core/yaml_reader.hpp"
#include "env/env_factory.hpp"
#include "env/imitation_env.hpp"

namespace mimic::test {

using Init = ImitationEnvConfig::Init;

// The clip turned by `yaw` about +Z and moved by `shift`: a start away from the track's.
inline std::shared_ptr<const Clip> moved(const Clip& clip, double yaw, const Vec3& shift) {
  Clip out = clip;
  const Quat r = heading_rotation(yaw);
  for (Pose& p : out.frames) {
    p.root_pos = r * p.root_pos + shift;
    p.rot[0] = r * p.rot[0];
  }
  return std::make_shared<const Clip>(std::move(out));
}

inline double term(const StepResult& r, const std::string& name) {
  for (const auto& [n, v] : r.reward_terms)
    if (n == name) return v;
  throw std::logic_error("no reward term " + name);
}

inline double max_joint_difference(const Pose& a, const Pose& b) {
  double d = 0;
  for (std::size_t j = 1; j < a.rot.size(); ++j)
    d = std::max(d, rotation_distance(a.rot[j], b.rot[j]));
  return d;
}

// The character up in the air, rigid (PD targets = its pose), flying along +X and sideways.
inline InitState flying(const CharacterModel& ch) {
  InitState s{rest_pose(ch.skeleton, Vec3(0, 0.4, 5.0)), PoseVelocity{}, 0.0, {}};
  s.velocity.root_lin = Vec3(2.0, 0.5, 0.0);
  s.velocity.joint_ang.assign(ch.skeleton.joints.size(), Vec3::Zero());
  return s;
}

// The error making an env factory from `env_yaml` gives, or "no error".
inline std::string factory_error(const YamlReader& r, const std::string& env_yaml) {
  try {
    (void)make_env_factory(r.parse(env_yaml, ""), r);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

// Steps with zero actions until the episode ends; returns the number of steps.
inline int run_zero_actions(CharacterEnv& env, StepResult& last) {
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(env.action_size());
  int steps = 0;
  do {
    last = env.step(zero);
    ++steps;
  } while (!last.done());
  return steps;
}

}  // namespace mimic::test
