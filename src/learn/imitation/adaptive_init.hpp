#pragma once
// Adaptive state initialisation (ASI, seed 003 section 7.1 and supplement A): the initial-state
// distribution is k independent Gaussians at fixed, evenly spaced phases of the reference clip
// (phase i at time i / k of its duration), each with a mean and a diagonal covariance over the
// character's state, learnt by the policy gradient of the episodes' discounted returns:
//   w <- w + step * F^-1 * mean over the batch of  grad_w log rho_w(s0) * (R0 - b)
// one step per batch of episodes (seed 003: 2,000 episodes). Two departures from the paper's
// plain gradient, both keeping the expected direction: b, the mean return of the batch's episodes
// from the same component, is a baseline (the paper uses none: far noisier); and F^-1, the
// inverse Fisher information of each parameter (sigma^2 for a mean, 1/2 for a log sigma), makes
// it the natural gradient, whose size does not depend on each dimension's units: the plain
// gradient of a mean grows as 1/sigma and blows up on dimensions the clip hardly moves. The step
// is therefore not the paper's 1e-3 (default 0.1: a mean moves about 0.1 sigma per update when
// the return correlates with it at 0.2 and the advantages are about 2).
//
// The state is a vector of offsets from the reference state at the component's phase (the means
// start at 0, i.e. at the reference, as in the paper): root height (1), root rotation (rotation
// vector, root frame: 3), each spherical joint's rotation (3) and revolute joint's angle (1),
// then the root's linear and angular velocity (world: 3 + 3) and each joint's angular velocity
// (3 or 1). The root's horizontal position stays the reference's. Standard deviations start at
// the clip's per-dimension sample standard deviation of these features (rotation vectors of the
// joint rotations; the root's tilt away from its heading; velocities), times `std_scale`, and
// are learnt as log sigma, never below `min_std`.
// Torch-free: plain Eigen, so that environments and tools can sample from a saved distribution.
#include <memory>
#include <random>

#include "env/character_env.hpp"
#include "learn/trainer/train_config.hpp"

namespace mimic {

class AdaptiveInit {
 public:
  // `clip` must fit `sk`. Throws Error on a bad config or a clip of fewer than 2 frames.
  AdaptiveInit(std::shared_ptr<const Clip> clip, const Skeleton& sk, const AdaptiveInitConfig& cfg);

  struct Draw {
    int component = 0;
    Eigen::VectorXd x;  // the offsets drawn
  };
  struct Outcome {
    int component = 0;
    Eigen::VectorXd x;
    double ret = 0.0;  // discounted return of the episode it started
  };

  int components() const { return cfg_.components; }
  int dims() const { return static_cast<int>(initial_std_.size()); }
  double phase_time(int component) const;  // seconds on the clip
  Draw draw(std::mt19937_64& rng) const;
  // The state that offsets `x` stand for at a component's phase.
  InitState state(int component, const Eigen::VectorXd& x) const;
  // One gradient step from a batch of episodes (components with fewer than 2 episodes in it
  // are left alone: their baseline would cancel their only sample).
  void update(const std::vector<Outcome>& batch);

  const AdaptiveInitConfig& config() const { return cfg_; }
  const Eigen::MatrixXd& means() const { return mean_; }  // components x dims
  const Eigen::MatrixXd& log_std() const { return log_std_; }
  const Eigen::VectorXd& initial_std() const { return initial_std_; }
  // Restores saved parameters; Error on a shape mismatch.
  void set_parameters(const Eigen::MatrixXd& means, const Eigen::MatrixXd& log_std);

 private:
  std::shared_ptr<const Clip> clip_;
  Skeleton sk_;
  AdaptiveInitConfig cfg_;
  Eigen::VectorXd initial_std_;
  Eigen::MatrixXd mean_, log_std_;
};

// A character environment whose episodes start from the distribution, recording each finished
// episode's component, offsets and discounted return (its own rewards; gamma as the learner's)
// for the trainer to collect between iterations. The distribution must not change while
// environments step (the trainer updates it between collections).
class AdaptiveInitEnv final : public Env {
 public:
  // Throws Error unless `inner` is a character environment.
  AdaptiveInitEnv(std::unique_ptr<Env> inner, std::shared_ptr<const AdaptiveInit> dist, double gamma);
  int observation_size() const override { return inner_->observation_size(); }
  int action_size() const override { return inner_->action_size(); }
  std::vector<ObservationSlice> observation_layout() const override { return inner_->observation_layout(); }
  Eigen::VectorXd reset(std::mt19937_64& rng) override;
  StepResult step(const Eigen::VectorXd& action) override;
  const mjModel_* physics_model() const override { return inner_->physics_model(); }
  mjData_* physics_data() const override { return inner_->physics_data(); }
  double control_dt() const override { return inner_->control_dt(); }
  int view_camera() const override { return inner_->view_camera(); }
  // Episodes finished since the last call, oldest first.
  std::vector<AdaptiveInit::Outcome> take_outcomes();

 private:
  std::unique_ptr<Env> inner_;
  CharacterEnv* character_;
  std::shared_ptr<const AdaptiveInit> dist_;
  double gamma_, discount_ = 1.0;
  AdaptiveInit::Outcome current_;
  std::vector<AdaptiveInit::Outcome> done_;
};

// Features of a state, laid out as the offsets (rotations as rotation vectors of the rotations
// themselves, the root's as its tilt away from its heading): what the initial std is taken of.
Eigen::VectorXd state_features(const Skeleton& sk, const Pose& pose, const PoseVelocity& vel);

}  // namespace mimic
