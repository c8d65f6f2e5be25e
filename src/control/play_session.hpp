#pragma once
// An interactive session over one character (what `mimic play` runs, in a window or from a
// script): skills requested by the user and taken over by the controller's switch rule, pushes
// and thrown cubes, the down rule, automatic recovery (seed 004 §6: a get-up skill takes over a
// fallen character, and the skill that was asked for takes it back by the score rule), and a log
// of what happened. Torch-free, draws nothing.
#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "env/down_rule.hpp"
#include "mimic/runtime.hpp"

namespace mimic {

struct PlayEvent {
  double t = 0.0;     // seconds since the session started (resets do not restart it)
  std::string event;  // request, switch, dropped, down, recovering, recovered, push, cube, steer, reset
  std::string skill;  // the requested skill, the one taking over, the active one
};

struct PlayOptions {
  SwitchRule rule;                    // how requested skills take over (the score rule by default)
  std::vector<std::string> recovery;  // skills that get a fallen character up; none: no recovery
  double push_force = 400.0;          // newtons, horizontal, on the root
  double push_seconds = 0.2;
  double down_height = 0.5;           // DownRule's
  int down_frames = 10;
  // The score (seed 004 eq. 6) at which the skill asked for takes the character back from a get-up
  // once the get-up is done (it has had the character for its clip's duration, the character is
  // up by the down rule, its root and its highest joint each at least 80 % of the heights they
  // have at the clip's end: standing, not bent over or kneeling); -1: at once
  // then. A skill's discriminators rate a character standing still low (the shipped walk's: -0.4
  // to -0.5 on the get-up clips' last frames), so a positive threshold may never hand back.
  double hand_back_threshold = -1.0;
  std::uint64_t seed = 1;             // starts, push directions
};

class PlaySession {
 public:
  // The first skill starts. Throws mimic::Error naming an unknown recovery skill.
  PlaySession(std::vector<std::shared_ptr<const Skill>> skills, PlayOptions options);

  // Asks for skill `index` (0-based, in the order given); false for no such skill. While the
  // character is being got up, the request waits for the get-up to end.
  bool request(std::size_t index);
  // Pushes the character's root horizontally along `direction` (world frame) with the options'
  // force; without a direction, along one drawn at random.
  void push(const Eigen::Vector3d& direction);
  void push();
  // Throws a cube at the torso; false where the active skill's world has none (Controller::throw_cube).
  bool throw_cube();
  // Turns the commanded heading by `degrees` (positive: to the left), from the last command or,
  // before one, from where the character faces; false (and nothing commanded) where no skill of
  // the session takes a heading (Controller::steerable).
  bool steer(double degrees);
  // A new start of the first skill.
  void reset();
  // One control step, and the events it brought.
  void step();

  double time() const { return time_; }
  bool down() const { return down_.down(); }
  bool recovering() const { return recovering_; }
  const std::string& wanted() const { return wanted_; }  // the skill asked for last (the first at the start)
  // Each skill's switch score of the current state (NaN for a skill without discriminators).
  std::vector<double> scores();
  const std::vector<PlayEvent>& events() const { return events_; }
  Controller& controller() { return controller_; }
  const PlayOptions& options() const { return options_; }

 private:
  void log(const std::string& event, const std::string& skill) { events_.push_back({time_, event, skill}); }
  void start_recovery();
  // The get-up for a character lying on `side` (Controller::lying_side): among those whose clip
  // begins on that side (all where none does, or the side is 0), the one whose discriminators
  // score the state highest; without discriminators, the first of them.
  std::string get_up_for(int side);
  void hand_to_get_up(const std::string& get_up);
  // The active get-up is done: it has had the character for its clip's duration, the character is
  // up by the down rule, and its root and its highest joint stand at least 80 % of the heights
  // they have at the clip's end (bent over, or kneeling, the highest joint is lower).
  bool get_up_done() const;
  void hand_back();  // the get-up is done: the skill asked for is requested by the hand-back's rule

  Controller controller_;
  PlayOptions options_;
  DownRule down_;
  std::string wanted_;
  bool recovering_ = false;
  std::vector<int> recovery_sides_;  // per recovery skill: the side its clip begins lying on, 0 if none
  int other_side_frames_ = 0;        // recovering: frames in a row lying on the other get-up's side
  std::vector<double> recovery_seconds_;  // per recovery skill: its clip's duration
  std::vector<double> recovery_heights_;  // and the root height above the ground it counts as standing
  std::vector<double> recovery_tops_;     // and the highest joint's height it counts as standing
  double get_up_since_ = 0.0;        // when the get-up that has the character took it
  bool handing_back_ = false;        // the get-up is done and the skill asked for is requested
  double time_ = 0.0;
  std::mt19937_64 rng_;
  std::vector<PlayEvent> events_;
};

}  // namespace mimic
