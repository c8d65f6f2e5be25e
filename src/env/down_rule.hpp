#pragma once
// Whether a character is down (seed 004 section 6.4's robustness protocol): what the projectile
// test counts as a failure, what a play session hands to a get-up skill, what a transition's
// target must not be during its hold.
namespace mimic {

// The robustness protocol's rule for a character that is down: lying — a body whose ground
// contact counts as a fall on the ground, or its root below `height` times its standing height —
// for `frames` control steps in a row. A crouch on its feet is neither. It is up again after as
// many steps in a row not lying.
class DownRule {
 public:
  DownRule(double standing_height, double height = 0.5, int frames = 10);
  // One control step's root height and fall contact; true at the step the character becomes down
  // (once per fall).
  bool update(double root_height, bool fall_contact = false);
  bool down() const { return down_; }
  void restart(double standing_height);

 private:
  double standing_, height_;
  int frames_, lying_ = 0, up_ = 0;
  bool down_ = false;
};

}  // namespace mimic
