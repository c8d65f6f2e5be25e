#pragma once
// A tiny environment for trainer tests: the observation is (step / 10, 1), one action, reward
// 1 - a^2 (so the best policy outputs 0), the step reported as the info "step"; episodes end by a time limit or by a "fall" at fixed
// steps, and can be made to emit a NaN reward.
#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>

#include "env/context_env.hpp"
#include "env/env.hpp"

namespace mimic::test {

class ToyEnv : public Env {
 public:
  explicit ToyEnv(int limit = 3, int fall_at = 0, int nan_at = 0) : limit_(limit), fall_at_(fall_at), nan_at_(nan_at) {}
  int observation_size() const override { return 2; }
  int action_size() const override { return 1; }
  std::vector<ObservationSlice> observation_layout() const override { return {{"toy", 0, 2}}; }
  Eigen::VectorXd reset(std::mt19937_64& rng) override {
    t_ = 0;
    (void)rng();
    return obs();
  }
  StepResult step(const Eigen::VectorXd& a) override {
    ++t_;
    StepResult r;
    r.observation = obs();
    r.reward_terms = {{"toy", nan_at_ > 0 && t_ == nan_at_ ? std::nan("") : 1.0 - a[0] * a[0]}};
    r.info = {{"step", t_}};  // reported, never rewarded
    if (fall_at_ > 0 && t_ == fall_at_) r.termination = Termination::Fall;
    else if (t_ >= limit_) r.termination = Termination::TimeLimit;
    return r;
  }

 private:
  Eigen::VectorXd obs() const { return Eigen::Vector2d(t_ / 10.0, 1.0); }
  int limit_, fall_at_, nan_at_, t_ = 0;
};

// A 1-D point mass (position x, velocity v; the action is a force, clipped to [-3, 3]) started
// on the unit circle of (x, v). The expert pushes with -x, so it oscillates as x = sin t: its
// states stay on the circle. The reward, which adversarial imitation never sees, is the squared
// distance of the radius from 1 (negated): a measure of how well a policy imitates.
class OscillatorEnv : public Env {
 public:
  static constexpr double kDt = 0.1;
  int observation_size() const override { return 2; }
  int action_size() const override { return 1; }
  std::vector<ObservationSlice> observation_layout() const override { return {{"position", 0, 1}, {"velocity", 1, 1}}; }
  Eigen::VectorXd reset(std::mt19937_64& rng) override {
    const double phase = std::uniform_real_distribution<double>(0.0, 2.0 * M_PI)(rng);
    x_ = std::sin(phase), v_ = std::cos(phase), t_ = 0;
    return Eigen::Vector2d(x_, v_);
  }
  StepResult step(const Eigen::VectorXd& a) override {
    v_ += std::clamp(a[0], -3.0, 3.0) * kDt;  // semi-implicit Euler keeps the expert's orbit closed
    x_ += v_ * kDt;
    ++t_;
    StepResult r;
    r.observation = Eigen::Vector2d(x_, v_);
    const double radius = std::hypot(x_, v_);
    r.reward_terms = {{"circle", -(radius - 1.0) * (radius - 1.0)}};
    if (t_ >= kLength) r.termination = Termination::TimeLimit;
    return r;
  }
  static constexpr int kLength = 40;

 private:
  double x_ = 0, v_ = 1;
  int t_ = 0;
};

// Mean radius over the second half of 10 oscillator episodes started on the unit circle, under
// behaviour context `context` of two held throughout, acting by `act` on (x, v, one-hot).
inline double held_orbit_radius(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& act, int context) {
  ContextEnv env(std::make_unique<OscillatorEnv>(), 2, 0);
  std::mt19937_64 rng(3);
  double sum = 0;
  int n = 0;
  for (int e = 0; e < 10; ++e) {
    Eigen::VectorXd obs = env.reset(rng);
    env.set_context(context);
    obs.tail(2) = Eigen::Vector2d(context == 0, context == 1);
    for (int k = 0; k < OscillatorEnv::kLength; ++k) {
      obs = env.step(act(obs)).observation;
      if (k >= OscillatorEnv::kLength / 2) sum += std::hypot(obs[0], obs[1]), ++n;
    }
  }
  return sum / n;
}

}  // namespace mimic::test
