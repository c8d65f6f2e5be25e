#include "learn/ppo/rollout.hpp"

namespace mimic {

Eigen::Map<const Eigen::VectorXd> Rollout::frame(int i) const {
  const std::size_t at = static_cast<std::size_t>(i) * static_cast<std::size_t>(input_size) +
                         static_cast<std::size_t>(input_size - frame_size);
  return Eigen::Map<const Eigen::VectorXd>(raw_input.data() + at, frame_size);
}

Eigen::Map<const Eigen::VectorXd> Rollout::next_frame(int i) const {
  return Eigen::Map<const Eigen::VectorXd>(next_obs.data() + static_cast<std::size_t>(i) * static_cast<std::size_t>(frame_size), frame_size);
}

Eigen::Map<const Eigen::VectorXf> Rollout::action_of(int i) const {
  return Eigen::Map<const Eigen::VectorXf>(action.data() + static_cast<std::size_t>(i) * static_cast<std::size_t>(action_size), action_size);
}

}  // namespace mimic
