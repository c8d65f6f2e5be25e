#pragma once
// Seed 000's behaviour context: one policy learns several behaviours (run straight, veer left,
// veer right) when a one-hot context c is appended to its observation and to what its
// discriminator sees. The context is drawn uniformly at every start and re-drawn every `period`
// steps during training (seed 000: every 5 s), so the policy also learns the transitions between
// behaviours; at run time a keyboard or a high-level controller sets it (set_context).
// With starts_by_context, an episode also starts from its context's own clip (the inner
// character env's start group of that index), so the context matches the motion it starts in.
#include <memory>
#include <optional>

#include "env/env.hpp"

namespace mimic {
class CharacterEnv;
}

namespace mimic {

// The part of an observation layout that holds the behaviour context's one-hot (ContextEnv's
// "context"), by value so that it outlives a temporary layout; empty when the layout has none.
std::optional<ObservationSlice> context_slice(const std::vector<ObservationSlice>& layout);

// The simulated character an environment drives: a behaviour-context env's through the env it
// wraps, a navigation env's (env/navigation_env.hpp) its skill's. Null when there is none (the
// walker, the arm).
CharacterEnv* character_of(Env& env);

class ContextEnv : public Env {
 public:
  // `contexts` >= 2; `period` steps between draws (0: only at reset). starts_by_context needs a
  // character env with one start group per context. Throws Error otherwise.
  ContextEnv(std::unique_ptr<Env> inner, int contexts, int period, bool starts_by_context = false);

  int observation_size() const override { return inner_->observation_size() + contexts_; }
  int action_size() const override { return inner_->action_size(); }
  // The inner layout, then {"context", inner size, contexts}.
  std::vector<ObservationSlice> observation_layout() const override;
  Eigen::VectorXd reset(std::mt19937_64& rng) override;
  StepResult step(const Eigen::VectorXd& action) override;
  const mjModel_* physics_model() const override { return inner_->physics_model(); }
  mjData_* physics_data() const override { return inner_->physics_data(); }
  double control_dt() const override { return inner_->control_dt(); }
  int view_camera() const override { return inner_->view_camera(); }

  int context() const { return context_; }
  void set_context(int c);  // Error outside [0, contexts); the next draw may change it
  // Holds context c (Error outside [0, contexts)) through draws and resets until release_context():
  // a user or a high-level controller choosing the behaviour. The observation shows it from the
  // next step or reset on.
  void hold_context(int c);
  void release_context() { held_ = false; }
  bool context_held() const { return held_; }
  int contexts() const { return contexts_; }
  int period() const { return period_; }  // steps between draws (0: only at reset)
  bool starts_by_context() const { return starts_by_context_; }
  Env& inner() { return *inner_; }  // the wrapped environment (e.g. to pose its character from a clip)

 private:
  Eigen::VectorXd with_context(const Eigen::VectorXd& obs) const;
  std::unique_ptr<Env> inner_;
  CharacterEnv* character_ = nullptr;  // inner_ when starts_by_context
  int contexts_, period_, context_ = 0, steps_ = 0;
  bool held_ = false;
  bool starts_by_context_ = false;
  std::mt19937_64 rng_;  // seeded from reset's generator: re-draws replay with the episode
};

}  // namespace mimic
