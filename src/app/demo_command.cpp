// mimic demo: the README's first command. Motion import, retargeting and pictures; then learning:
// a tracking policy trained for about four minutes on the built-in squat, evaluated (imitation
// error before and after) and filmed with the clip as a ghost; with ../shared, the project's best
// skills (the ICCGAN walk, run, kick and punch of seed 004's Table 2) evaluated and filmed the
// same way; then the finale, one scripted play session of those skills with recovery (the walk
// takes over into a punch, a kick, a punch, the walk again and the run; the character is pushed
// down, gets up and walks on), filmed with its events.
#include <spdlog/spdlog.h>

#include <cmath>
#include <optional>

#include "app/commands.hpp"
#include "core/file_io.hpp"
#include "motion/builtin.hpp"
#include "motion/bvh.hpp"
#include "motion/deepmimic.hpp"
#include "motion/retarget.hpp"
#include "motion/retarget_maps.hpp"
#include "core/build_paths.hpp"
#include "render/clip_video.hpp"
#include "core/error.hpp"
#include "app/play_run.hpp"
#include "app/policy_video.hpp"
#include "app/run_skill.hpp"
#include "control/skill_impl.hpp"
#include "env/tracking.hpp"
#include "learn/imitation/imitation_eval.hpp"
#include "learn/trainer/trainer.hpp"

namespace mimic::app {

namespace {

// The demo's training: about four minutes on two cores.
constexpr int kDemoIterations = 300;

// The finale's switch rule: a requested skill takes over once its discriminators score the
// character's motion at least this (docs/interactive.md, the transition test).
constexpr double kFinaleTau = -0.2;
// Long enough for the get-up and the walk on after the script's last key.
constexpr double kFinaleSeconds = 30.0;

// Summary, .mclip, .svg picture and (unless disabled) an .mp4 of the clip on `ch`.
void show(const Clip& clip, const CharacterModel& ch, const std::filesystem::path& dir, double seconds, bool video,
          double azimuth, std::string& summary) {
  const std::string text = clip_summary(clip);
  fmt::print("{}\n", text);
  summary += text + "\n";
  write_motion(clip, dir / (clip.name + ".mclip"));
  write_motion(clip, dir / (clip.name + ".svg"));
  if (!video) return;
  ClipVideoOptions opts;
  opts.width = 480, opts.height = 360, opts.seconds = seconds, opts.ghost = true;
  opts.camera.azimuth = azimuth;
  try {
    const auto out = dir / (clip.name + ".mp4");
    const int frames = render_clip_video(ch, clip, out, opts);
    spdlog::info("rendered {} ({} frames; the translucent ghost replays the clip)", out.string(), frames);
  } catch (const Error& e) {
    spdlog::warn("no video: {}", e.what());
  }
}

// The skill's imitation of its environment's clip: "error 0.123 +- 0.010 m, normalised return 0.45".
// Against `clip` where given (a skill whose environment has no reference of its own).
std::string imitation_line(const Skill& skill, int trials, const Clip* clip = nullptr) {
  const std::unique_ptr<Env> env = make_skill_env(skill);
  auto& character = dynamic_cast<CharacterEnv&>(*env);
  const PolicyFunction act = [&](const Eigen::VectorXd& x) { return skill.act(x); };
  const ImitationReport r = measure_imitation(character, act, skill.history(), trials, clip);
  // The normalised return is a tracking reward's; other skills have none.
  const double normalised = r.normalised_return_mean();
  return fmt::format("imitation error {:.3f} +- {:.3f} m over {} phases, {}{} of {} down ({} fell){}", r.error_mean(), r.error_std(), trials,
                     std::isfinite(normalised) ? fmt::format("normalised return {:.3f}, ", normalised) : "", r.down, trials, r.falls,
                     r.trial_progress.empty() ? "" : fmt::format(", progress {:.2f}", r.progress_mean()));
}

void film(const Skill& skill, const std::filesystem::path& out, double seconds) {
  PolicyVideoOptions o;
  o.width = 480, o.height = 360, o.seconds = seconds, o.ghost = true;
  try {
    const std::unique_ptr<Env> env = make_skill_env(skill);
    const PolicyVideoStats s = render_policy_video(*env, [&skill](const Eigen::VectorXd& x) { return skill.act(x); }, skill.history(), out, o);
    spdlog::info("rendered {} ({} frames; the translucent ghost is the reference)", out.string(), s.frames);
  } catch (const Error& e) {
    spdlog::warn("no video: {}", e.what());
  }
}

// The shipped model of each of seed 004's Table 2 skills (models/README.md).
std::string best_model(const std::string& skill) {
  if (skill == "walk") return "humanoid_walk_iccgan";
  if (skill == "run") return "humanoid_run_iccgan_straight_loop";
  if (skill == "kick") return "humanoid_kick_iccgan_total";
  return "humanoid_punch_iccgan_annealed";
}

// Seed 003's tracking on a built-in clip and body: a few minutes of PPO from scratch.
void learn_builtin(const Clip& learnt, const std::filesystem::path& dir, int iterations, int trials, bool video, std::string& summary) {
  const auto ch = std::make_shared<const CharacterModel>(CharacterModel::from_skeleton(learnt.skeleton, "builtin_humanoid"));
  const auto clip = std::make_shared<const Clip>(learnt);
  const std::string name = learnt.name;
  TrackingConfig tc;
  tc.env.fall_links = {"root", "chest", "neck"};  // everything but limbs ends an episode
  tc.env.max_seconds = 6.0;
  TrainOptions opts;
  opts.run_dir = dir / (name + "_run");
  std::filesystem::remove_all(opts.run_dir);
  opts.env_factory = [ch, clip, tc] { return std::unique_ptr<Env>(make_tracking_env(*ch, clip, tc)); };
  opts.on_iteration = [iterations](const IterationMetrics& m) {
    if (m.iteration % 10 == 0 || m.iteration == iterations)
      spdlog::info("  iteration {:3}/{}: {:7.0f} samples, reward per step {:.3f}", m.iteration, iterations, m.get("samples"), m.get("reward"));
  };
  const std::string config = fmt::format(
      "# mimic demo: tracking a built-in clip (seed 003's reward, random-phase starts)\n"
      "seed: 1\niterations: {}\ncheckpoint_every: 20\ncollect: {{envs: 8, threads: 2, samples: 2048}}\n"
      "policy: {{hidden: [128, 128], activation: relu, log_std: -2.0, learn_std: false}}\nvalue: {{hidden: [128, 128], activation: relu}}\n"
      "ppo: {{gamma: 0.95, lambda: 0.95, epochs: 5, value_epochs: 5, minibatch: 256, kl_target: 0.02}}\n"
      "optimizer: {{policy_lr: 1.0e-3, value_lr: 1.0e-3}}\n",
      iterations);
  Trainer trainer(parse_train_config(config, "mimic demo"), opts);
  // The policy acts on the runtime (control/), from the trainer's networks as export writes them.
  auto skill = [&] { return skill_in(opts.env_factory, trainer.runtime_networks(), opts.run_dir / "checkpoint.pt", name); };
  const std::string before = imitation_line(*skill(), trials);
  spdlog::info("learning: tracking the {} ({} iterations of 2,048 samples; before training: {})", name, iterations, before);
  trainer.run();
  const std::shared_ptr<const Skill> trained = skill();
  const std::string after = imitation_line(*trained, trials);
  const std::string line = fmt::format("learning    {} tracked after {} samples: {} (untrained: {}); run in {}", name, trainer.samples(),
                                       after, before, opts.run_dir.string());
  fmt::print("{}\n", line);
  summary += line + "\n";
  if (video) film(*trained, dir / (name + "_policy.mp4"), 6.0);
}

// The finale's skills, in the order its script's keys 1-5 request them, and the get-ups of its
// recovery (models/README.md; the session's script is configs/play/finale.txt).
const std::vector<std::string> kFinaleSkills = {"humanoid_walk_iccgan_from_skills", "humanoid_run_iccgan_from_skills",
                                                "humanoid_kick_iccgan_from_skills", "humanoid_punch_iccgan_annealed",
                                                "humanoid_walk_iccgan_after_getups"};
const std::vector<std::string> kFinaleGetUps = {"humanoid_getup_facedown", "humanoid_getup_faceup"};

// The finale's session: the arguments of `mimic play` that make it (where every model is there).
std::optional<PlayArgs> finale_args() {
  const std::filesystem::path source(kSourceDir);
  PlayArgs a;
  for (const auto* list : {&kFinaleSkills, &kFinaleGetUps})
    for (const std::string& name : *list) {
      const std::filesystem::path model = source / "models" / name;
      if (!std::filesystem::exists(model / "networks.mimic")) return std::nullopt;
      (list == &kFinaleSkills ? a.models : a.recover).push_back(model);
    }
  a.script = source / "configs/play/finale.txt";
  a.rule = "score", a.tau = kFinaleTau, a.time_limit = 3.0;
  a.push_force = 900;
  a.headless = true, a.seconds = kFinaleSeconds;
  a.seed = 1;
  return a;
}

// The same session as a command line, for the log and the docs (paths relative to the source directory).
std::string play_command_line(const PlayArgs& a) {
  std::string line = "mimic play";
  const std::filesystem::path source(kSourceDir);
  auto rel = [&](const std::filesystem::path& p) { return std::filesystem::relative(p, source).string(); };
  for (const auto& m : a.models) line += " " + rel(m);
  line += " --recover";
  for (const auto& m : a.recover) line += " " + rel(m);
  return line + fmt::format(" --script {} --tau {} --time-limit {} --push-force {} --seed {} --seconds {} (in the source directory)", rel(a.script), a.tau,
                            a.time_limit, a.push_force, a.seed, a.seconds);
}

// The finale, into dir/finale.mp4 (with `video`) and dir/finale.json: its events in one line.
void finale(const std::filesystem::path& dir, bool video, std::string& summary) {
  std::optional<PlayArgs> a = finale_args();
  if (!a) {
    spdlog::info("the finale's models are not all in models/ (models/README.md): no finale");
    return;
  }
  if (video) a->output = dir / "finale.mp4";
  a->json = dir / "finale.json";
  spdlog::info("the finale: {}", play_command_line(*a));
  std::vector<PlayEvent> events;
  try {
    events = run_play(*a);
  } catch (const Error& e) {  // the rest of the demo is kept
    spdlog::warn("no finale: {}", e.what());
    return;
  }
  std::string story;
  for (const PlayEvent& e : events) {
    if (e.event == "request" || e.event == "push" || e.event == "cube") continue;
    std::string skill = e.skill;
    if (skill.rfind("humanoid_", 0) == 0) skill = skill.substr(9);
    story += fmt::format("{}{} {} {:.1f} s", story.empty() ? "" : ", ", e.event, skill, e.t);
  }
  const std::string line = "finale      " + (story.empty() ? std::string("nothing happened") : story) + " (" + a->json.string() + ")";
  fmt::print("{}\n", line);
  summary += line + "\n";
}

}  // namespace

void add_demo_command(CLI::App& app) {
  auto out = std::make_shared<std::filesystem::path>("out/demo");
  auto video = std::make_shared<bool>(true);
  auto iterations = std::make_shared<int>(kDemoIterations);
  auto trials = std::make_shared<int>(10);
  CLI::App* demo = app.add_subcommand("demo", "run mimic's showcase on built-in (and, if present, shared) motion");
  demo->add_option("-o,--output", *out, "output directory")->capture_default_str();
  demo->add_flag("!--no-video", *video, "skip the videos (pictures and clips only)");
  demo->add_option("--train-iterations", *iterations, "PPO iterations of 2,048 samples of the squat's tracking policy (0: skip learning)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  demo->add_option("--trials", *trials, "evaluation trials of each policy (evenly spaced phases of its clip)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  demo->callback([out, video, iterations, trials] {
    std::string summary;
    // 1. Motion the project authors itself, on a simple body: always available.
    const Clip jack = builtin_jumping_jack(), squat = builtin_squat();
    show(jack, CharacterModel::from_skeleton(jack.skeleton, "builtin_humanoid"), *out, 3.0, *video, 160.0, summary);
    show(squat, CharacterModel::from_skeleton(squat.skeleton, "builtin_humanoid"), *out, 4.0, *video, 120.0, summary);
    if (*iterations > 0) learn_builtin(squat, *out, *iterations, *trials, *video, summary);
    // 2. Real capture: CMU walk retargeted onto the DeepMimic humanoid, when ../shared is here.
    const auto data = shared_data_dir();
    const auto bvh = data / "cmu-bvh/131_01.bvh", ch = data / "deepmimic/characters/humanoid3d.txt";
    if (!data.empty() && std::filesystem::exists(bvh) && std::filesystem::exists(ch)) {
      const CharacterModel humanoid = CharacterModel::from_deepmimic(ch, data / "deepmimic/characters/humanoid3d_ctrl.txt");
      // 2. DeepMimic's walk on the simulated humanoid.
      const Clip walk_clip = load_deepmimic_motion(data / "deepmimic/motions/humanoid3d_walk.txt", humanoid.skeleton);
      show(walk_clip, humanoid, *out, 4.0, *video, 120.0, summary);
      // 3. Real capture: CMU walk retargeted onto the same humanoid.
      RetargetReport report;
      Clip clip = retarget(load_bvh(bvh, AxisConvention{"y", "z", 0.056444}), humanoid.skeleton, builtin_retarget_map("cmu_to_humanoid3d"), &report);
      clip.name = "cmu131_01_on_humanoid3d";
      show(clip, humanoid, *out, 0.0, *video, 120.0, summary);
      const std::string rep = "retarget    " + retarget_summary(report);
      fmt::print("{}", rep);
      summary += rep;
      // 4. The project's best skills (seed 004's ICCGAN, Table 2), on the runtime as a program would run them.
      for (const char* skill : {"walk", "run", "kick", "punch"}) {
        const auto model = std::filesystem::path(kSourceDir) / "models" / best_model(skill);
        if (!std::filesystem::exists(model / "networks.mimic")) continue;
        const Clip reference = std::string(skill) == "walk" ? walk_clip
                                                             : load_deepmimic_motion(data / ("deepmimic/motions/humanoid3d_" + std::string(skill) + ".txt"),
                                                                                     humanoid.skeleton);
        const std::shared_ptr<const Skill> policy = run_skill(model);
        const std::string line = "pretrained  " + model.filename().string() + ": " + imitation_line(*policy, *trials, &reference);
        fmt::print("{}\n", line);
        summary += line + "\n";
        if (*video) film(*policy, *out / (model.filename().string() + "_policy.mp4"), 8.0);
      }
      // 5. The finale: those skills in one scripted session, with recovery.
      finale(*out, *video, summary);
    } else {
      spdlog::info("shared data not found (../shared/data or $MIMIC_DATA): showing the built-in clip only");
    }
    write_file_atomic(*out / "summary.txt", summary);
    spdlog::info("wrote clips (.mclip), pictures (.svg), videos (.mp4) and summary.txt to {}", out->string());
  });
}

}  // namespace mimic::app
