// A play session from its arguments: what `mimic play` runs, and the demo's finale
// (docs/interactive.md).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "control/play_session.hpp"

namespace mimic::app {

struct PlayArgs {
  std::vector<std::filesystem::path> models, recover;  // keys 1, 2, ... in this order; the first starts
  std::string rule = "score";                         // score, value or immediately
  double tau = 0.2, time_limit = 2.0, recover_tau = -1.0;
  int delay = 0;
  std::filesystem::path script, output, json, screenshot, motion;  // empty: none
  double seconds = 0;  // 0: in a window until closed; headless, 2 s past the script's last key
  bool headless = false;
  int width = 960, height = 540;
  double push_force = 400, cube_mass = 5, cube_speed = 5;
  std::uint64_t seed = 1;
};

// Runs the session (in a window, or headless as fast as it can), writes what `a` asks for, and
// returns its events. Throws mimic::Error for arguments that do not make a session, a bad script
// line (naming the file and line) or models that cannot play together.
std::vector<PlayEvent> run_play(const PlayArgs& a);

}  // namespace mimic::app
