#pragma once
// Another body from a DeepMimic character: its segments lengthened or shortened and its mass
// changed, written back as DeepMimic character and PD-controller files (seed 003's Atlas
// experiment tracks motion on a body heavier and otherwise proportioned than the capture's).
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace mimic {

struct CharacterScaling {
  // A part of a joint name and a length factor: every joint whose name contains the part takes
  // the factor (a later entry over an earlier one; "*" is every joint). A joint's factor scales
  // the bodies and draw shapes attached to it (their place and size) and the offsets of its
  // child joints: the segment from the joint onwards.
  std::vector<std::pair<std::string, double>> lengths;
  double mass = 1.0;   // every body's mass times this
  double gains = 0.0;  // Kp, Kd and torque limits times this; 0: mass times the mean length factor
};

struct ScaledCharacter {
  std::string character;       // the DeepMimic character file's text
  std::vector<double> factors;  // each joint's length factor, by joint index
  double gains = 1.0;           // the factor the gains and torque limits took
};

// The character file `text` (read from `source`, for messages) scaled. Throws Error naming the
// source on a malformed file, a factor that is not positive and finite, or a name part that no
// joint has.
ScaledCharacter scale_deepmimic_character(std::string_view text, const std::string& source, const CharacterScaling& scaling);

// A DeepMimic PD-controller file's text with every Kp and Kd times `gains`.
std::string scale_deepmimic_controller(std::string_view text, const std::string& source, double gains);

}  // namespace mimic
