// mimic record RUN -o demos.csv: expert demonstrations from a trained policy, for adversarial
// imitation (rewards: [{source: gail, expert: demos.csv}]); mimic clone: the behavioural-cloning
// baseline.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "app/commands.hpp"
#include "core/config_file.hpp"
#include "core/error.hpp"
#include "core/statistics.hpp"
#include "core/file_io.hpp"
#include "env/context_env.hpp"
#include "env/env_factory.hpp"
#include "app/run_skill.hpp"
#include "control/skill_impl.hpp"
#include "learn/imitation/clip_demonstrations.hpp"
#include "learn/trainer/trainer.hpp"
#include "motion/clip_io.hpp"

namespace mimic::app {

void add_imitation_commands(CLI::App& app) {
  struct Args {
    std::filesystem::path run, out;
    int episodes = 50, every = 20;
    bool deterministic = false;
    std::uint64_t seed = 7;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand("record", "record expert demonstrations (CSV) from a trained policy's episodes");
  cmd->add_option("run", args->run, "training run directory (config.yaml + checkpoint.pt)")->required()->check(CLI::ExistingDirectory);
  cmd->add_option("-o,--output", args->out, "output .csv")->required();
  cmd->add_option("--episodes", args->episodes, "episodes to record")->capture_default_str()->check(CLI::PositiveNumber);
  cmd->add_option("--every", args->every, "keep every N-th step of each episode (seed 002: 20)")->capture_default_str()->check(CLI::PositiveNumber);
  cmd->add_flag("--deterministic", args->deterministic, "act with the policy's mean instead of sampling (default: sample, as seed 002)");
  cmd->add_option("--seed", args->seed, "random seed (initial states, action noise, sub-sampling offsets)")->capture_default_str();
  cmd->callback([args] {
    // The runtime's episodes, as training would have run them (control/episodes.hpp).
    const std::shared_ptr<const Skill> skill = run_skill(args->run);
    EpisodeOptions o = training_episodes(args->run);
    o.episodes = args->episodes, o.seed = args->seed, o.deterministic = args->deterministic;
    std::mt19937_64 rng(args->seed);  // action noise, then the sub-sampling offsets
    EpisodeStats stats;
    const Rollout episodes = run_episodes(*skill, o, rng, stats);
    const Demonstrations d = demonstrations_of(episodes, skill->impl().layout, args->every, rng);
    write_demonstrations(args->out, d);
    spdlog::info("wrote {}: {} samples from {} episodes (every {} steps), mean episode return {:.1f}", args->out.string(), d.size(),
                 d.episodes(), args->every, mean_of(stats.returns));
  });

  struct ClipArgs {
    std::filesystem::path config, character, out;
    std::vector<std::filesystem::path> clips;
    int passes = 4;
  };
  auto clip_args = std::make_shared<ClipArgs>();
  CLI::App* rc = app.add_subcommand("record-clip", "demonstrations from a motion clip: the environment's observations of its states (no actions)");
  rc->add_option("config", clip_args->config, "training config whose env is a character environment (e.g. imitation)")
      ->required()->check(CLI::ExistingFile);
  rc->add_option("--clip", clip_args->clips, "motion clip (.mclip, .bvh, .amc, DeepMimic .txt); repeat it for several clips in one file")
      ->required()
      ->check(CLI::ExistingFile);
  rc->add_option("--character", clip_args->character, "DeepMimic character file of a .txt clip (default: found by its name)");
  rc->add_option("--passes", clip_args->passes, "passes over the clip, offset by a fraction of a control step")->capture_default_str()->check(CLI::PositiveNumber);
  rc->add_option("-o,--output", clip_args->out, "output .csv")->required();
  rc->callback([clip_args] {
    const TrainConfig cfg = load_train_config(clip_args->config);
    if (!cfg.env.IsDefined()) throw Error(clip_args->config.string() + ": no 'env' section");
    const std::unique_ptr<Env> env = make_env_factory(cfg.env, YamlReader(cfg.source))();
    // A behaviour context is not part of a clip's demonstrations: the discriminator appends each
    // file's own one-hot (imitation.md), so a context env records through the env it wraps.
    auto* context_env = dynamic_cast<ContextEnv*>(env.get());
    auto* character_env = dynamic_cast<CharacterEnv*>(context_env ? &context_env->inner() : env.get());
    if (!character_env) throw Error(clip_args->config.string() + ": its environment has no simulated character to pose from a clip");
    LoadOptions load;
    load.character = clip_args->character;
    std::vector<Clip> clips;
    std::string names;
    for (const auto& path : clip_args->clips) {
      clips.push_back(load_motion(path, load));
      names += (names.empty() ? "" : ", ") + clips.back().name;
    }
    const Demonstrations d = clip_demonstrations(*character_env, clips, clip_args->passes);
    write_demonstrations(clip_args->out, d);
    spdlog::info("wrote {}: {} transitions of {} ({} pass{} each), {} observation values", clip_args->out.string(), d.size(), names,
                 clip_args->passes, clip_args->passes == 1 ? "" : "es", d.obs.cols());
  });

  struct CloneArgs {
    std::filesystem::path config, expert, out;
    int episodes = 0, epochs = 200, batch = 64;
    double lr = 1e-3;
  };
  auto clone = std::make_shared<CloneArgs>();
  CLI::App* bc = app.add_subcommand("clone", "behavioural cloning: fit a policy's mean to demonstrations (the baseline of adversarial imitation)");
  bc->add_option("config", clone->config, "training config (.yaml): environment and policy network")->required()->check(CLI::ExistingFile);
  bc->add_option("--expert", clone->expert, "demonstrations (.csv, from mimic record)")->required()->check(CLI::ExistingFile);
  bc->add_option("--episodes", clone->episodes, "use the first N episodes of the file (0: all)")->capture_default_str()->check(CLI::NonNegativeNumber);
  bc->add_option("--epochs", clone->epochs, "passes over the demonstrations")->capture_default_str()->check(CLI::PositiveNumber);
  bc->add_option("--lr", clone->lr, "Adam learning rate")->capture_default_str()->check(CLI::PositiveNumber);
  bc->add_option("--batch", clone->batch, "minibatch size")->capture_default_str()->check(CLI::PositiveNumber);
  bc->add_option("-o,--out", clone->out, "run directory to write (config.yaml + checkpoint.pt)")->required();
  bc->callback([clone] {
    if (std::filesystem::exists(clone->out / "checkpoint.pt")) throw Error(clone->out.string() + " already holds a run (checkpoint.pt)");
    Demonstrations d = read_demonstrations(clone->expert);
    if (clone->episodes > 0) {
      if (d.episodes() < clone->episodes)
        throw Error(d.source + ": " + std::to_string(d.episodes()) + " episodes, fewer than --episodes " + std::to_string(clone->episodes));
      d = d.first_episodes(clone->episodes);
    }
    // The clone learns from no reward: its run must load without the config's expert files.
    const std::string text = override_config(read_config_file(clone->config), clone->config.string(), {"rewards=[{source: env}]"});
    Trainer trainer(parse_train_config(text, clone->config.string()));
    const double loss = trainer.clone_behaviour(d, clone->epochs, clone->lr, clone->batch, trainer.config().seed);
    std::filesystem::create_directories(clone->out);
    write_file_atomic(clone->out / "config.yaml", text);
    trainer.save_checkpoint(clone->out / "checkpoint.pt");
    spdlog::info("cloned {} samples ({} episodes) in {} epochs: final mean squared error {:.4f}; wrote {}", d.size(), d.episodes(),
                 clone->epochs, loss, clone->out.string());
  });

  // The discriminators' view of a motion: seed 004 switches policies by these scores, and a
  // context run's discriminator that tells its contexts apart scores a clip higher under its own.
  struct ScoreArgs {
    std::filesystem::path run, demos, json;
    int context = -1;
  };
  auto score = std::make_shared<ScoreArgs>();
  CLI::App* sc = app.add_subcommand("score", "a run's discriminator rewards for demonstrations (how expert-like it finds them), per behaviour context");
  sc->add_option("run", score->run, "training run or model directory (config.yaml + checkpoint.pt) with gail or iccgan rewards")
      ->required()
      ->check(CLI::ExistingDirectory);
  sc->add_option("--demos", score->demos, "demonstrations (.csv, from mimic record or record-clip)")->required()->check(CLI::ExistingFile);
  sc->add_option("--context", score->context, "behaviour context to score under (default: each of the run's; none without)")
      ->check(CLI::NonNegativeNumber);
  sc->add_option("--json", score->json, "also write the scores as JSON");
  sc->callback([score] {
    const std::shared_ptr<const Skill> skill = run_skill(score->run, {}, /*discriminators=*/true);
    if (skill->discriminators().empty())
      throw Error(score->run.string() + ": this run has no discriminator (rewards with source gail or iccgan) to score with");
    const Demonstrations d = read_demonstrations(score->demos);
    // The run's own observation without its context: what record-clip and record write.
    const std::unique_ptr<Env> env = make_skill_env(*skill);
    const auto* contexts_env = dynamic_cast<const ContextEnv*>(env.get());
    const int own = skill->frame_size() - (contexts_env ? contexts_env->contexts() : 0);
    if (d.obs.cols() != own)
      throw Error(d.source + ": demonstrations have " + std::to_string(d.obs.cols()) + " observation values, this run's environment " +
                  std::to_string(own) + " (without its context)");
    std::vector<int> contexts{score->context};
    if (score->context < 0 && contexts_env) {
      contexts.clear();
      for (int k = 0; k < contexts_env->contexts(); ++k) contexts.push_back(k);
    }
    spdlog::info("{}: {} transitions scored by {}", d.source, d.size(), score->run.string());
    std::string rows;
    for (int context : contexts) {
      for (const std::string& source : skill->discriminators()) {
        const Eigen::VectorXd scores = skill->score(source, d.obs, d.next_obs, d.action, context);
        const std::vector<double> values(scores.begin(), scores.end());
        const double mean = mean_of(values), sd = std_of(values);
        const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
        spdlog::info("  {:<10} {:<11} reward {:.3f} +- {:.3f} (min {:.3f}, max {:.3f})", source,
                     context < 0 ? "" : fmt::format("context {}", context), mean, sd, *lo, *hi);
        rows += fmt::format("{}{{\"source\": {}, \"context\": {}, \"mean\": {}, \"std\": {}, \"min\": {}, \"max\": {}}}",
                            rows.empty() ? "" : ", ", json_string(source), context < 0 ? "null" : std::to_string(context), json_number(mean),
                            json_number(sd), json_number(*lo), json_number(*hi));
      }
    }
    if (!score->json.empty())
      write_file_atomic(score->json, fmt::format("{{\"run\": {}, \"demos\": {}, \"transitions\": {}, \"scores\": [{}]}}\n",
                                                 json_string(score->run.string()), json_string(d.source), d.size(), rows));
  });
}

}  // namespace mimic::app
