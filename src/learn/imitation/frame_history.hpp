#pragma once
// The last K observation frames of one environment, stacked oldest first into a policy input.
// A new episode fills every slot with its first frame. Torch-free: tools that play policies use it.
#include <Eigen/Core>
#include <deque>

namespace mimic {

class FrameHistory {
 public:
  explicit FrameHistory(int frames = 1) : size_(frames) {}
  void reset(const Eigen::VectorXd& first) { frames_.assign(static_cast<std::size_t>(size_), first); }
  void push(const Eigen::VectorXd& frame) {
    frames_.pop_front();
    frames_.push_back(frame);
  }
  Eigen::VectorXd stacked() const {
    const Eigen::Index n = frames_.front().size();
    Eigen::VectorXd x(n * size_);
    for (int f = 0; f < size_; ++f) x.segment(f * n, n) = frames_[static_cast<std::size_t>(f)];
    return x;
  }

 private:
  int size_;
  std::deque<Eigen::VectorXd> frames_;
};

}  // namespace mimic
