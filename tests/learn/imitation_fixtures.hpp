#pragma once
// The point-mass imitation fixtures shared by imitation_test.cpp and context_imitation_test.cpp:
// the oscillator's expert, a GAIL config on it, and the two orbits that the behaviour-context
// tests teach one policy.
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "env/context_env.hpp"
#include "learn/imitation/demonstrations.hpp"
#include "learn/trainer/trainer.hpp"
#include "toy_env.hpp"
#include "trainer_access.hpp"

namespace mimic::test {

// The expert of OscillatorEnv (force -x) for `episodes` episodes, every step kept.
inline Demonstrations oscillator_expert(int episodes) {
  test::OscillatorEnv env;
  std::mt19937_64 rng(11);
  const int n = episodes * test::OscillatorEnv::kLength;
  Demonstrations d;
  d.obs.resize(n, 2), d.action.resize(n, 1), d.next_obs.resize(n, 2);
  int i = 0;
  for (int e = 0; e < episodes; ++e) {
    Eigen::VectorXd obs = env.reset(rng);
    for (bool done = false; !done; ++i) {
      const Eigen::VectorXd a = Eigen::VectorXd::Constant(1, -obs[0]);
      const StepResult r = env.step(a);
      d.obs.row(i) = obs.transpose(), d.action.row(i) = a.transpose(), d.next_obs.row(i) = r.observation.transpose();
      d.episode.push_back(e);
      obs = r.observation, done = r.done();
    }
  }
  return d;
}

inline void write(const std::filesystem::path& p, const std::string& text) { std::ofstream(p) << text; }

inline TrainOptions oscillator_options() {
  TrainOptions o;
  o.env_factory = [] { return std::make_unique<test::OscillatorEnv>(); };
  return o;
}

inline std::string gail_config(const std::filesystem::path& expert, int iterations, const std::string& extra = "") {
  return "seed: 2\n"
         "iterations: " + std::to_string(iterations) + "\n"
         "collect: {envs: 8, threads: 1, samples: 1024}\n"
         "policy: {hidden: [32, 32], log_std: -0.5}\n"
         "value: {hidden: [32, 32]}\n"
         "ppo: {gamma: 0.95, epochs: 5, value_epochs: 5, minibatch: 128}\n"
         "rewards:\n"
         "  - {source: gail, expert: " + expert.string() + ", network: {hidden: [32, 32]}" + extra + "}\n";
}

// Two behaviours for the context tests, written to dir/small.csv and dir/large.csv: the
// oscillator's orbit of radius 1 and the same orbit at radius 2 (force -x still orbits).
struct TwoOrbits {
  Demonstrations small, large;
  std::string experts;  // "experts: [<small.csv>, <large.csv>]"
};

inline TwoOrbits two_orbits(const std::filesystem::path& dir, int episodes, const std::vector<ObservationSlice>& layout = {}) {
  TwoOrbits o;
  o.small = oscillator_expert(episodes);
  o.small.layout = layout;
  o.large = o.small;
  o.large.obs *= 2, o.large.action *= 2, o.large.next_obs *= 2;
  write_demonstrations(dir / "small.csv", o.small);
  write_demonstrations(dir / "large.csv", o.large);
  o.experts = "experts: [" + (dir / "small.csv").string() + ", " + (dir / "large.csv").string() + "]";
  return o;
}

// A gail_config on `single` with its expert replaced by `experts` (and whatever follows them).
inline std::string with_experts(std::string text, const std::filesystem::path& single, const std::string& experts) {
  const std::string key = "expert: " + single.string();
  return text.replace(text.find(key), key.size(), experts);
}

inline TrainOptions context_oscillator_options(int period = 0) {
  TrainOptions o;
  o.env_factory = [period] { return std::make_unique<ContextEnv>(std::make_unique<test::OscillatorEnv>(), 2, period); };
  return o;
}

// The toy's held_orbit_radius, acting with the trainer's mean action.
inline double held_radius(Trainer& t, int context) {
  return test::held_orbit_radius([&t](const Eigen::VectorXd& obs) { return test::act(t, obs); }, context);
}
}  // namespace mimic::test
