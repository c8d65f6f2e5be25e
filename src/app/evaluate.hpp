#pragma once
// `mimic eval`'s measurement as a function: `mimic imitate` evaluates the model it made with it.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "mimic/runtime.hpp"

namespace mimic::app {

struct EvalArgs {
  std::filesystem::path run, json, clip, character;
  int episodes = 20, trials = 20;
  int context = -1;  // a behaviour context held for the imitation trials (-1: none given)
  bool latency = false;
  std::vector<int> switches;  // behaviour contexts whose every ordered pair is a switch to measure
  double switch_seconds = 5.0;
  std::vector<double> masses;  // robustness: projectile masses (kg)
  int robustness_trials = 20;
  double robustness_seconds = 10.0;
  bool stochastic = false;
  std::uint64_t seed = 12345;
  std::vector<std::string> settings;  // env.KEY=VALUE overrides of the run's config, in memory
  std::vector<std::filesystem::path> transitions;  // other skills of the character: switch to and from each
  int transition_trials = 20;
  std::vector<std::string> transition_rules{"score", "value", "matching", "immediately"};
  std::vector<double> transition_taus;  // empty: TransitionOptions::thresholds
  std::vector<std::filesystem::path> recover;  // get-up skills: robustness with recovery at each mass of `masses`
  double recover_tau = -1.0;  // the score at which the skill takes the character back from a get-up that is done
  bool goal_along_clip = false;  // imitation trials of a skill with a heading goal: commanded along the clip's path
  std::vector<double> steering;  // commanded turns (degrees) for a skill with a heading goal
  int steering_trials = 20;
  bool crossing = false;  // the run's course (or --set env.terrain's) crossed
  int crossing_trials = 20;
  double crossing_seconds = 20.0;
  std::vector<double> fixed_action;  // a baseline: the episodes with this action in place of the policy's
  // Each episode in its own environment (not the training's collect.envs taking turns; at most 32
  // side by side, a group at a time): for the same --episodes and --seed, episode k starts the
  // same, on the same course, whatever the policy does, and its return is reported in episode
  // order, so two evaluations compare episode by episode.
  bool paired = false;
};

// Measures the run or model directory `args.run` as `mimic eval` does: a table on the terminal,
// and the figures as JSON into args.json where given.
void evaluate(const EvalArgs& args);

// The measurements in runtime sessions (app/eval_sessions.cpp), each as its JSON member with a
// leading ", ": the transition test between `skill` and args.transitions, robustness with
// recovery by args.recover, and the response to steering commands.
std::string transitions(const EvalArgs& args, const std::shared_ptr<const Skill>& skill);
std::string recovery(const EvalArgs& args);
// Steering (learn/imitation/steering_eval.hpp) at each turn of args.steering.
std::string steering(const EvalArgs& args);
// The course crossed (learn/imitation/crossing_eval.hpp), args.crossing_trials times.
std::string crossing(const EvalArgs& args);
// The run's environment for seed 004's projectile test at `mass` (0: no cubes): the user's --set,
// then cubes at the torso every frame and episodes a second longer than --robustness-seconds.
std::vector<std::string> projectile_settings(const EvalArgs& args, double mass);

}  // namespace mimic::app
