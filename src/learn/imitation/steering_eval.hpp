#pragma once
// Steering (seed 004 eq. 8's heading goal as a command): how quickly a skill trained with
// `goal: heading` turns to a commanded direction and walks along it. A trial starts from the
// environment's own start, walks `settle_seconds` towards where it faces, then is commanded a
// turn of +-turn_degrees (alternating) from its heading and holds it `hold_seconds`. The heading
// error at a step is the angle between the command and the root's horizontal travel over the last
// `travel_seconds` (a gait's sway averaged out). The environment's own redraws must be off
// (goal_period longer than a trial): the command is the only target.
#include <cstdint>
#include <vector>

#include "learn/imitation/imitation_eval.hpp"

namespace mimic {

struct SteeringOptions {
  double turn_degrees = 90.0;
  int trials = 20;
  double settle_seconds = 2.0, hold_seconds = 4.0;
  double travel_seconds = 0.5;
  double respond_seconds = 2.0;  // the error is read this long after the command
  double tolerance_degrees = 15.0;
  std::uint64_t seed = 1;
};

struct SteeringReport {
  double turn_degrees = 0, respond_seconds = 0, tolerance_degrees = 0;
  int trials = 0, falls = 0;                // falls: trials that went down (a fall or the down rule) before the end
  std::vector<double> error_degrees;        // per standing trial: the heading error respond_seconds after the command
  std::vector<double> seconds_to_tolerance;  // per standing trial: the first time within tolerance (infinity: never)
  std::vector<double> speed_along;          // per standing trial: m/s along the command over the hold's second half
  // Trials within tolerance at respond_seconds, of all trials (a fall counts as a miss).
  double success_rate() const;
};

// The angle in degrees, in [0, 180], between a horizontal travel (world x, y; z ignored) and the
// direction at world yaw `target_yaw`; 180 for no horizontal travel (standing still follows nothing).
double heading_error_degrees(const Vec3& travel, double target_yaw);

// Throws Error when `env` has no heading goal, or for options out of range.
SteeringReport measure_steering(CharacterEnv& env, const PolicyFunction& act, int history, const SteeringOptions& options);

}  // namespace mimic
