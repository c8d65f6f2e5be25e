#pragma once
// One iteration's experience from N environments. Samples are stored flat; `env_steps[e]` lists
// environment e's samples in time order, so advantages and returns run along each environment.
// Torch-free: reward sources and tools read it without LibTorch headers.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace mimic {

struct Rollout {
  int input_size = 0;   // policy input: history frames x frame size
  int frame_size = 0;   // one observation of the environment
  int action_size = 0;
  int envs = 0;

  // Row-major [samples, width] buffers.
  std::vector<double> raw_input;  // policy input before normalisation (the normaliser learns from it)
  std::vector<float> input;       // normalised input the policy saw
  std::vector<double> next_obs;   // the environment's observation after the step (the last one of an ended episode)
  std::vector<float> action, mean;  // sampled action, and the policy mean it was drawn around
  std::vector<float> log_std;       // [samples, actions]
  std::vector<float> value;        // V(s_t) under the acting value network
  std::vector<double> env_reward;      // the environment's task reward (sum of its terms)
  std::vector<double> reward;          // what the learner optimises (weighted reward sources)
  std::vector<double> next_value;      // V of the state after the step (bootstrap of ended/last steps)
  std::vector<std::uint8_t> ended, failed;
  std::vector<std::vector<int>> env_steps;

  // Sums of each reward term of the environment over the rollout.
  std::vector<std::pair<std::string, double>> term_sums;
  // Sums of each value the environment reports besides its reward (StepResult::info).
  std::vector<std::pair<std::string, double>> info_sums;

  int size() const { return static_cast<int>(env_reward.size()); }
  Eigen::Map<const Eigen::VectorXd> frame(int i) const;     // current observation (last frame of the input)
  Eigen::Map<const Eigen::VectorXd> next_frame(int i) const;
  Eigen::Map<const Eigen::VectorXf> action_of(int i) const;
};

// Finished episodes seen while collecting (episodes span iterations in horizon mode).
struct EpisodeStats {
  std::vector<double> returns;  // sum of the environment's reward
  std::vector<int> lengths;
  int failures = 0;
};

}  // namespace mimic
