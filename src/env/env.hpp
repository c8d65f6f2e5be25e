#pragma once
// The environment interface every task and learner uses: reset to an initial state, step with
// an action, get an observation, named reward terms and why (or whether) the episode ended.
#include <Eigen/Core>
#include <random>
#include <string>
#include <utility>
#include <vector>

struct mjModel_;
struct mjData_;

namespace mimic {

enum class Termination {
  None,       // the episode goes on
  Fall,       // a failure: a body that must not touch the ground did (or a task's failure rule)
  TimeLimit,  // truncated by the episode's length: not a failure, bootstrap the value
  ClipEnd,    // a non-cyclic reference clip ended
  Drift,      // a failure: the root strayed too far from the reference's (a tracking rule)
};
const char* to_string(Termination t);
// True for endings after which the return is cut off (not bootstrapped): failures.
inline bool is_failure(Termination t) { return t == Termination::Fall || t == Termination::Drift; }

struct StepResult {
  Eigen::VectorXd observation;
  std::vector<std::pair<std::string, double>> reward_terms;  // name, value; the task sums them
  // What the task reports besides its reward (a curriculum's level, say): name, value; never
  // rewarded. The trainer logs each one's mean over an iteration's steps as info_<name>.
  std::vector<std::pair<std::string, double>> info;
  Termination termination = Termination::None;
  bool done() const { return termination != Termination::None; }
  double reward() const {
    double r = 0;
    for (const auto& [name, v] : reward_terms) r += v;
    return r;
  }
};

// Which part of an observation vector holds what (observation builders are selected by name).
struct ObservationSlice {
  std::string name;
  int offset = 0, size = 0;
};

class Env {
 public:
  virtual ~Env() = default;
  virtual int observation_size() const = 0;
  virtual int action_size() const = 0;
  virtual std::vector<ObservationSlice> observation_layout() const = 0;
  // A fresh episode; `rng` draws whatever the environment randomises (initial state, targets).
  virtual Eigen::VectorXd reset(std::mt19937_64& rng) = 0;
  // One control step. Actions outside the documented range are clipped, never rejected.
  virtual StepResult step(const Eigen::VectorXd& action) = 0;
  // The MuJoCo model and state behind the environment, for rendering; null when there is none.
  virtual const mjModel_* physics_model() const { return nullptr; }
  virtual mjData_* physics_data() const { return nullptr; }
  // Simulated seconds per step(); 0 where the environment does not say (wrappers pass on their inner one's).
  virtual double control_dt() const { return 0.0; }
  // The physics model's camera that films this environment best (its index), or -1: a camera
  // that follows the root from the side (videos, `mimic play`).
  virtual int view_camera() const { return -1; }
};

}  // namespace mimic
