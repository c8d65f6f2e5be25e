// mimic render RUN: a trained policy acting in its environment (mean actions), filmed with
// MuJoCo's offscreen renderer. Episodes that end start again, so falls stay visible.
#include <mujoco/mujoco.h>
#include <spdlog/spdlog.h>

#include <cmath>

#include "app/policy_video.hpp"
#include "core/error.hpp"
#include "env/character_env.hpp"
#include "env/context_env.hpp"
#include "learn/imitation/frame_history.hpp"
#include "app/run_skill.hpp"
#include "control/skill_impl.hpp"
#include "render/offscreen.hpp"
#include "render/video_writer.hpp"

namespace mimic::app {

PolicyVideoStats render_policy_video(const std::filesystem::path& run, const std::filesystem::path& out, const PolicyVideoOptions& opts) {
  const std::shared_ptr<const Skill> skill = run_skill(run, opts.env_settings);
  const std::unique_ptr<Env> env = make_skill_env(*skill);
  try {
    return render_policy_video(*env, [&skill](const Eigen::VectorXd& x) { return skill->act(x); }, skill->history(), out, opts);
  } catch (const Error& e) {
    throw Error(run.string() + ": " + e.what());
  }
}

PolicyVideoStats render_policy_video(Env& env_ref, const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& act, int history,
                                     const std::filesystem::path& out, const PolicyVideoOptions& opts) {
  Env* const env = &env_ref;
  mjData* const data = env->physics_data();
  if (!env->physics_model() || !data) throw Error("its environment has nothing to draw");

  // Contexts held in turn from the first step on (validated before anything is written).
  auto* behaviours = dynamic_cast<ContextEnv*>(env);
  if (!opts.contexts.empty() && !behaviours) throw Error("--contexts: its environment has no behaviour context");
  for (int c : opts.contexts)
    if (c < 0 || c >= behaviours->contexts())
      throw Error("--contexts: context " + std::to_string(c) + " is outside the run's 0 to " + std::to_string(behaviours->contexts() - 1));
  if (!opts.contexts.empty()) behaviours->hold_context(opts.contexts.front());

  std::mt19937_64 rng(opts.seed);
  FrameHistory frames(history);
  auto start_episode = [&] { frames.reset(env->reset(rng)); };
  start_episode();
  // Steps per video frame: the environment's control step, brought near opts.fps.
  const double control_dt = env->control_dt();
  if (!(control_dt > 0)) throw Error("the environment does not say its control step");
  PolicyVideoStats stats;
  StepResult r = env->step(act(frames.stacked()));
  const int every = std::max(1, static_cast<int>(std::lround(1.0 / (opts.fps * control_dt))));
  const double fps = 1.0 / (every * control_dt);
  const int steps = static_cast<int>(std::lround(opts.seconds / control_dt));
  const int context_steps = std::max(1, static_cast<int>(std::lround(opts.context_seconds / control_dt)));

  // The ghost: the pose the character is measured against (CharacterEnv::reference_pose), in a
  // second data of the same model.
  // A behaviour-context env draws its character through the env it wraps.
  const auto* character = dynamic_cast<const CharacterEnv*>(behaviours ? &behaviours->inner() : env);
  if (opts.ghost && (!character || (!character->reference() && !character->start_source().clip)))
    throw Error("--ghost needs an environment with a reference clip (tracking) or starts drawn from clips (init: mocap)");
  std::unique_ptr<mjData, void (*)(mjData*)> ghost(opts.ghost ? mj_makeData(env->physics_model()) : nullptr, mj_deleteData);
  OffscreenRenderer renderer(env->physics_model(), opts.width, opts.height);
  VideoWriter video(out, opts.width, opts.height, fps);
  std::vector<std::uint8_t> rgb;
  CameraFollow follow;
  const int own_camera = env->view_camera();  // an environment's own view (the reacher's from above), else the one following the root
  double episode_return = 0;
  for (int t = 1; t <= steps; ++t) {
    if (behaviours && !opts.contexts.empty() && t % context_steps == 0) {
      const int next = opts.contexts[static_cast<std::size_t>(t / context_steps) % opts.contexts.size()];
      if (next != behaviours->context()) spdlog::info("  {:.2f} s: context {}", t * control_dt, next);
      behaviours->hold_context(next);
    }
    if (t > 1) r = env->step(act(frames.stacked()));
    episode_return += r.reward();
    frames.push(r.observation);
    const Vec3 look = follow.update(Vec3(data->xpos[3], data->xpos[4], data->xpos[5]));  // body 1: the root
    if (t % every == 0) {
      CameraSpec cam = opts.camera;
      cam.lookat = Vec3(look.x(), look.y(), opts.camera.lookat.z());
      cam.model_camera = own_camera;
      // A start without a clip (a fixed pose) has no ghost until an episode that starts on one.
      if (ghost) {
        if (const std::optional<Pose> ref = character->reference_pose()) character->world().write_pose(*ref, ghost.get());
      }
      renderer.render(data, cam, rgb, ghost.get());
      video.write(rgb);
    }
    if (r.done()) {
      stats.episodes.push_back({episode_return, r.termination});
      episode_return = 0;
      start_episode();
      follow.restart();
    }
  }
  video.close();
  stats.frames = video.frames();
  stats.fps = fps;
  return stats;
}

}  // namespace mimic::app
