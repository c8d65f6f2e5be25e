#include "env/context_env.hpp"

#include "core/error.hpp"

namespace mimic {

ContextEnv::ContextEnv(std::unique_ptr<Env> inner, int contexts, int period) : inner_(std::move(inner)), contexts_(contexts), period_(period) {
  if (!inner_) throw Error("context: no environment to wrap");
  if (contexts < 2) throw Error("context: needs at least 2 contexts, got " + std::to_string(contexts));
  if (period < 0) throw Error("context: the period must be >= 0 steps");
}

std::vector<ObservationSlice> ContextEnv::observation_layout() const {
  std::vector<ObservationSlice> layout = inner_->observation_layout();
  layout.push_back({"context", inner_->observation_size(), contexts_});
  return layout;
}

Eigen::VectorXd ContextEnv::with_context(const Eigen::VectorXd& obs) const {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(obs.size() + contexts_);
  out.head(obs.size()) = obs;
  out[obs.size() + context_] = 1.0;
  return out;
}

Eigen::VectorXd ContextEnv::reset(std::mt19937_64& rng) {
  const Eigen::VectorXd obs = inner_->reset(rng);
  rng_.seed(rng());
  const int drawn = std::uniform_int_distribution<int>(0, contexts_ - 1)(rng_);
  if (!held_) context_ = drawn;  // drawn either way: a held context leaves the episode's draws as they were
  steps_ = 0;
  return with_context(obs);
}

StepResult ContextEnv::step(const Eigen::VectorXd& action) {
  StepResult r = inner_->step(action);
  ++steps_;
  if (period_ > 0 && steps_ % period_ == 0) {
    const int drawn = std::uniform_int_distribution<int>(0, contexts_ - 1)(rng_);
    if (!held_) context_ = drawn;
  }
  r.observation = with_context(r.observation);
  return r;
}

void ContextEnv::set_context(int c) {
  if (c < 0 || c >= contexts_) throw Error("context " + std::to_string(c) + " is outside [0, " + std::to_string(contexts_) + ")");
  context_ = c;
}

void ContextEnv::hold_context(int c) {
  set_context(c);
  held_ = true;
}

}  // namespace mimic
