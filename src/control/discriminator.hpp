#pragma once
// A discriminator a skill was trained against, evaluated with Eigen in float32 as
// learn/rewards/discriminator.cpp computes its reward with LibTorch: the transition's features (chosen
// observation entries of s', of (s, s') or of (s, a), each state followed by a behaviour
// context's one-hot where it has one), standardised, through the network, and its heads' outputs
// turned into a reward: seed 004 eq. 5's mean of clip(D_i, -1, 1) for the hinge ensemble, or
// GAIL's -log(1 - D) (log D, or the logit) clipped, plus the configured offset. Immutable once read.
#include <string>
#include <vector>

#include "control/network.hpp"

namespace mimic {

struct SkillDiscriminator {
  std::string source;  // the reward source's name (gail, iccgan)
  int context = -1;    // >= 0: the discriminator of that behaviour context alone (per_context)
  std::string transition = "s";  // s | ss | sa
  std::vector<int> columns;      // chosen entries of an observation frame
  int contexts = 0;              // > 0: a one-hot context follows each state's entries
  int action_size = 0;
  std::string loss = "hinge", reward = "neg_log_one_minus_d";
  double reward_clip = 10.0, reward_offset = 0.0;
  Eigen::RowVectorXf input_mean, input_std;
  Network net;

  int state_width() const { return static_cast<int>(columns.size()) + contexts; }
  int width() const;
  // Discriminator "discriminator.<index>." of a skill file whose frames have `frame_size` values
  // and whose actions `action_size`. Error naming the file and the array.
  static SkillDiscriminator read(const ArrayTable& t, int index, int frame_size, int action_size);
  // The reward of each transition (rows: observation frames without their context, the next
  // frames, the actions) under behaviour context `held` (-1 where the features have none).
  Eigen::VectorXd rewards(const Eigen::MatrixXd& obs, const Eigen::MatrixXd& next_obs, const Eigen::MatrixXd& actions, int held) const;
  // Seed 004 eq. 6's switch score of the same transitions, in [-1, 1] whatever the reward's offset:
  // the mean over heads of clip(D_i, -1, 1) for the hinge ensemble; for GAIL's classifier the mean
  // of 2 sigmoid(logit) - 1 (its probability of the expert, on the same scale).
  Eigen::VectorXd switch_scores(const Eigen::MatrixXd& obs, const Eigen::MatrixXd& next_obs, const Eigen::MatrixXd& actions, int held) const;
  // The network's outputs [rows, heads] for the transitions' standardised features.
  FloatMatrix outputs(const Eigen::MatrixXd& obs, const Eigen::MatrixXd& next_obs, const Eigen::MatrixXd& actions, int held) const;
};

}  // namespace mimic
