#include "env/context_env.hpp"

#include "core/error.hpp"
#include "env/character_env.hpp"
#include "env/navigation_env.hpp"

namespace mimic {

ContextEnv::ContextEnv(std::unique_ptr<Env> inner, int contexts, int period, bool starts_by_context)
    : inner_(std::move(inner)), contexts_(contexts), period_(period), starts_by_context_(starts_by_context) {
  if (!inner_) throw Error("context: no environment to wrap");
  if (contexts < 2) throw Error("context: needs at least 2 contexts, got " + std::to_string(contexts));
  if (period < 0) throw Error("context: the period must be >= 0 steps");
  if (starts_by_context) {
    character_ = dynamic_cast<CharacterEnv*>(inner_.get());
    const int groups = character_ ? character_->start_groups() : 0;
    if (groups != contexts)
      throw Error("context: starts by context need one start clip per context: " + std::to_string(contexts) + " contexts, " +
                  std::to_string(groups) + " clips to start from");
  }
}

std::optional<ObservationSlice> context_slice(const std::vector<ObservationSlice>& layout) {
  for (const ObservationSlice& s : layout)
    if (s.name == "context") return s;
  return std::nullopt;
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
  // Drawn either way: a held context leaves the episode's draws as they were. Starting from the
  // context's clip needs the context first; otherwise the inner env draws first, as it always has.
  auto draw = [&] {
    rng_.seed(rng());
    const int drawn = std::uniform_int_distribution<int>(0, contexts_ - 1)(rng_);
    if (!held_) context_ = drawn;
  };
  Eigen::VectorXd obs;
  if (character_) {
    draw();
    character_->choose_start_group(context_);
    obs = inner_->reset(rng);
  } else {
    obs = inner_->reset(rng);
    draw();
  }
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

CharacterEnv* character_of(Env& env) {
  if (auto* navigation = dynamic_cast<NavigationEnv*>(&env)) return &navigation->character();
  auto* contexts = dynamic_cast<ContextEnv*>(&env);
  return dynamic_cast<CharacterEnv*>(contexts ? &contexts->inner() : &env);
}

}  // namespace mimic
