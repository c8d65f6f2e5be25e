#include "env/down_rule.hpp"

#include "core/error.hpp"

namespace mimic {

DownRule::DownRule(double standing_height, double height, int frames) : standing_(standing_height), height_(height), frames_(frames) {
  if (!(height > 0 && height < 1) || frames < 1) throw Error("down rule: the height must be a fraction in (0, 1) and the frames >= 1");
}

bool DownRule::update(double root_height, bool fall_contact) {
  if (!fall_contact && root_height >= height_ * standing_) {
    lying_ = 0;
    // Up again once as many frames in a row are above as it took to be down (a root that bounces
    // while the character lies is not a new fall).
    if (down_ && ++up_ >= frames_) down_ = false, up_ = 0;
    return false;
  }
  up_ = 0;
  if (down_) return false;
  if (++lying_ < frames_) return false;
  down_ = true;
  return true;
}

void DownRule::restart(double standing_height) {
  standing_ = standing_height;
  lying_ = up_ = 0;
  down_ = false;
}

}  // namespace mimic
