#pragma once
// Videos of trained policies (mimic render RUN).
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "env/env.hpp"
#include "render/offscreen.hpp"

namespace mimic::app {

struct PolicyVideoOptions {
  double seconds = 10.0;
  double fps = 30.0;  // approximate: a whole number of control steps per frame
  int width = 640, height = 480;
  std::uint64_t seed = 1;
  bool ghost = false;  // the environment's reference clip drawn translucent over the character
  // A policy over behaviour contexts: hold these in turn, each for context_seconds (empty: the
  // environment draws its own).
  std::vector<int> contexts;
  double context_seconds = 5.0;
  std::vector<std::string> env_settings;  // env.KEY=VALUE over the run's config (a run or model directory)
  CameraSpec camera{Vec3(0, 0, 0.9), 4.0, 90.0, -12.0};  // lookat z: height of the point followed
};

struct PolicyVideoStats {
  int frames = 0;
  double fps = 0;
  std::vector<std::pair<double, Termination>> episodes;  // return and ending of each episode that ended
};

// Plays a run or model directory's policy deterministically (mean actions) on the torch-free
// runtime (app/run_skill.hpp) and writes `out` (.mp4/.gif).
PolicyVideoStats render_policy_video(const std::filesystem::path& run, const std::filesystem::path& out, const PolicyVideoOptions& opts);
// Any policy: `act` maps `history` stacked observations of `env` (oldest first) to an action.
PolicyVideoStats render_policy_video(Env& env, const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& act, int history,
                                     const std::filesystem::path& out, const PolicyVideoOptions& opts);

}  // namespace mimic::app
