// mimic eval RUN: one measurement for every policy (DESIGN.md section 5): episode return, length
// and fall rate; for a character with a reference clip (the env's own, or --clip), the imitation
// error over one cycle from evenly spaced phases and the normalised return; with --robustness,
// seed 004's projectile test (frames survived per cube mass; with --recover, the fraction of the
// time performing without and with get-up skills); with --latency, the policy's
// forward-pass time at batch 1 and, for an adversarial run, its discriminators'; with --switch, a
// policy over behaviour contexts changing behaviour on command; with --steering, a skill with a
// heading goal turning on command; with --crossing, how often the skill gets over a course. A
// table on the terminal, and the same figures as JSON with --json.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "app/commands.hpp"
#include "app/evaluate.hpp"
#include "core/error.hpp"
#include "core/json_text.hpp"
#include "core/file_io.hpp"
#include "core/statistics.hpp"
#include "env/character_env.hpp"
#include "env/context_env.hpp"
#include "env/env_factory.hpp"
#include "learn/imitation/context_switch.hpp"
#include "learn/imitation/imitation_eval.hpp"
#include "learn/trainer/train_config.hpp"
#include "app/run_skill.hpp"
#include "control/episodes.hpp"
#include "control/runtime_cost.hpp"
#include "control/skill_impl.hpp"

namespace mimic::app {

std::string json_string(const std::string& s) { return json_quoted(s); }

std::string json_number(double v) { return std::isfinite(v) ? fmt::format("{}", v) : "null"; }

std::string json_numbers(const std::vector<double>& v) {
  std::string out = "[";
  for (std::size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + json_number(v[i]);
  return out + "]";
}

namespace {


// The `count` links with the largest values of a per-link vector, largest first: "right_wrist 0.312, ...".
std::string largest_links(const ImitationReport& r, const std::vector<double>& per_link, std::size_t count) {
  std::vector<std::size_t> order(per_link.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return per_link[a] > per_link[b]; });
  std::string out;
  for (std::size_t i = 0; i < std::min(count, order.size()); ++i)
    out += fmt::format("{}{} {:.3f}", i ? ", " : "", r.link_names[order[i]], per_link[order[i]]);
  return out + " m";
}

// {"root": 0.1, ...}: a per-link vector by link name.
std::string links_json(const ImitationReport& r, const std::vector<double>& per_link) {
  std::string out = "{";
  for (std::size_t j = 0; j < per_link.size(); ++j)
    out += fmt::format("{}{}: {}", j ? ", " : "", json_string(r.link_names[j]), json_number(per_link[j]));
  return out + "}";
}

// The policy as a function of the character env's (stacked) observations. A policy over behaviour
// contexts needs --context: the held context's one-hot goes after every stacked frame, as
// ContextEnv appends it to every observation.
PolicyFunction policy_on_character(const EvalArgs& args, const std::shared_ptr<const Skill>& skill, Env& env) {
  auto* contexts = dynamic_cast<ContextEnv*>(&env);
  if (args.context >= 0 && !contexts) throw Error(args.run.string() + ": --context: this run's environment has no behaviour context");
  if (!contexts) return [skill](const Eigen::VectorXd& input) { return skill->act(input); };
  const int k = contexts->contexts(), frame = contexts->inner().observation_size();
  if (args.context < 0)
    throw Error(args.run.string() + ": its policy takes a behaviour context: give --context K (0 to " + std::to_string(k - 1) + ")");
  if (args.context >= k)
    throw Error(args.run.string() + ": --context " + std::to_string(args.context) + ": the run has contexts 0 to " + std::to_string(k - 1));
  const Eigen::VectorXd one_hot = Eigen::VectorXd::Unit(k, args.context);
  return [skill, k, frame, one_hot](const Eigen::VectorXd& input) {
    const Eigen::Index frames = input.size() / frame;
    Eigen::VectorXd with(frames * (frame + k));
    for (Eigen::Index f = 0; f < frames; ++f) {
      with.segment(f * (frame + k), frame) = input.segment(f * frame, frame);
      with.segment(f * (frame + k) + frame, k) = one_hot;
    }
    return skill->act(with);
  };
}

// The user's --set overrides, then the command's own (which win where both name a key).
std::vector<std::string> with_settings(const EvalArgs& args, const std::vector<std::string>& own) {
  std::vector<std::string> all = args.settings;
  all.insert(all.end(), own.begin(), own.end());
  return all;
}

}  // namespace

std::vector<std::string> projectile_settings(const EvalArgs& args, double mass) {
  return with_settings(args, {mass > 0 ? fmt::format("env.projectiles={{enabled: true, mass: {}}}", mass) : "env.projectiles={enabled: false}",
                              fmt::format("env.max_seconds={}", args.robustness_seconds + 1.0)});
}

namespace {

// Seed 004's projectile test at each mass: the run's environment rebuilt with projectiles on.
std::string robustness(const EvalArgs& args, const RunNetworks& networks) {
  const int max_frames = static_cast<int>(std::lround(args.robustness_seconds * 30.0));
  spdlog::info("  robustness      cubes of 0.2 m at 0.2 m/s at the torso every frame; {} trials per mass, at most {} frames; "
               "failure: lying on the ground 10 frames",
               args.robustness_trials, max_frames);
  std::string json = ", \"robustness\": [";
  for (std::size_t i = 0; i < args.masses.size(); ++i) {
    const double mass = args.masses[i];
    const std::shared_ptr<const Skill> skill = load_skill(
        args.run, networks.bytes, networks.source, "",
        projectile_settings(args, mass));
    const std::unique_ptr<Env> env = make_skill_env(*skill);
    CharacterEnv* character = character_of(*env);
    if (!character) throw Error(args.run.string() + ": robustness needs a character environment");
    if (std::abs(character->config().sim.control_hz - 30.0) > 1e-9)
      throw Error(args.run.string() + ": robustness counts frames at 30 Hz; this environment runs at " +
                  std::to_string(character->config().sim.control_hz) + " Hz");
    const PolicyFunction act = policy_on_character(args, skill, *env);
    const RobustnessReport r = measure_robustness(*character, act, skill->history(), args.robustness_trials, max_frames);
    spdlog::info("    {}     {:.1f} +- {:.1f} frames survived", mass > 0 ? fmt::format("{:6.2f} kg", mass) : std::string("no cubes "), r.mean(), r.std());
    json += fmt::format("{}{{\"mass\": {}, \"frames_mean\": {}, \"frames_std\": {}, \"trials\": {}, \"max_frames\": {}}}", i ? ", " : "", mass,
                        r.mean(), r.std(), r.frames.size(), max_frames);
  }
  return json + "]";
}

// Seed 004 Table 4's runtime cost, on the runtime (what a program embedding the skill pays): one
// policy forward pass at batch 1 (input normalisation and the mean action included) and one
// reward of each discriminator at batch 1; medians of 2,000 passes on this machine's core.
std::string latency(const EvalArgs& args, const std::shared_ptr<const Skill>& acting) {
  std::shared_ptr<const Skill> skill = acting;
  if (skill->discriminators().empty()) {
    const std::filesystem::path config = args.run / "config.yaml";
    const TrainConfig cfg = parse_train_config(read_text_file(config), config.string());
    if (std::any_of(cfg.rewards.begin(), cfg.rewards.end(), [](const RewardSourceConfig& r) { return r.source != "env"; })) {
      try {
        skill = run_skill(args.run, args.settings, /*discriminators=*/true);
      } catch (const Error& e) {  // the policy's figures stand; say why the discriminators' are missing
        spdlog::warn("  latency         discriminator not measured: {}", e.what());
      }
    }
  }
  const RuntimeCost policy = policy_cost(*skill);
  spdlog::info("  latency         policy forward pass at batch 1: {:.0f} us median; {} parameters ({:.2f} MB as float32)", policy.microseconds,
               policy.parameters, policy.megabytes());
  std::string json = fmt::format(", \"latency\": {{\"policy_us\": {}, \"policy_parameters\": {}, \"discriminators\": [", policy.microseconds,
                                 policy.parameters);
  const std::vector<RuntimeCost> costs = discriminator_costs(*skill);
  for (std::size_t i = 0; i < costs.size(); ++i) {
    const RuntimeCost& c = costs[i];
    spdlog::info("  latency         {} discriminator reward at batch 1: {:.0f} us median; {} parameters ({:.2f} MB as float32)", c.name,
                 c.microseconds, c.parameters, c.megabytes());
    json += fmt::format("{}{{\"source\": {}, \"us\": {}, \"parameters\": {}}}", i ? ", " : "", json_string(c.name), c.microseconds,
                        c.parameters);
  }
  return json + "]}";
}

// Seed 000's context switches: every ordered pair of the listed contexts, each held switch_seconds.
std::string context_switches(const EvalArgs& args, const std::shared_ptr<const Skill>& skill) {
  const std::unique_ptr<Env> env = make_skill_env(*skill);
  auto* contexts = dynamic_cast<ContextEnv*>(env.get());
  if (!contexts) throw Error(args.run.string() + ": --switch: this run's environment has no behaviour context");
  std::vector<int> distinct = args.switches;
  std::sort(distinct.begin(), distinct.end());
  if (std::adjacent_find(distinct.begin(), distinct.end()) != distinct.end())
    throw Error(args.run.string() + ": --switch lists a context twice; give each once, e.g. --switch 0,1");
  if (args.switches.size() < 2) throw Error(args.run.string() + ": --switch needs two or more contexts, e.g. --switch 0,1");
  // Holds are timed at the character's control rate (other environments do not state theirs).
  const CharacterEnv* character = character_of(*env);
  if (!character) throw Error(args.run.string() + ": --switch needs a character environment (its control rate times the holds)");
  const double hz = character->config().sim.control_hz;
  const int hold = std::max(2, static_cast<int>(std::lround(args.switch_seconds * hz)));
  spdlog::info("  switches        context held {:.2f} s, then the other for as long; {} trials a pair from the env's own starts (mean actions); "
               "speed: horizontal, of the root, over each hold's second half",
               hold / hz, args.trials);
  std::string json = ", \"switches\": [";
  bool first = true;
  for (int from : args.switches) {
    for (int to : args.switches) {
      if (from == to) continue;
      const SwitchReport r = measure_switch(
          *contexts, [&skill](const Eigen::VectorXd& input) { return skill->act(input); }, skill->history(), from,
          to, args.trials, hold, args.seed);
      spdlog::info("    {} -> {}       fell {} before the switch, {} after; speed {:.2f} +- {:.2f} -> {:.2f} +- {:.2f} m/s", from, to,
                   r.fell_before, r.fell_after, mean_of(r.speed_before), std_of(r.speed_before), mean_of(r.speed_after),
                   std_of(r.speed_after));
      json += fmt::format("{}{{\"from\": {}, \"to\": {}, \"trials\": {}, \"hold_seconds\": {}, \"fell_before\": {}, \"fell_after\": {}, "
                          "\"speed_before_mean\": {}, \"speed_before_std\": {}, \"speed_after_mean\": {}, \"speed_after_std\": {}}}",
                          first ? "" : ", ", from, to, r.trials, r.hold_seconds, r.fell_before, r.fell_after,
                          json_number(mean_of(r.speed_before)), json_number(std_of(r.speed_before)), json_number(mean_of(r.speed_after)),
                          json_number(std_of(r.speed_after)));
      first = false;
    }
  }
  return json + "]";
}

}  // namespace

void evaluate(const EvalArgs& args) {
  // Only the environment may change: the policy's shape and training are the checkpoint's.
  for (const std::string& setting : args.settings)
    if (setting.rfind("env.", 0) != 0)
      throw Error("--set " + setting + ": eval overrides environment keys only (env.KEY=VALUE, e.g. env.max_seconds=30)");
  if (!args.recover.empty() && args.masses.empty())
    throw Error("--recover measures under the projectile test: give the cube masses with --robustness");
  const RunNetworks networks = run_networks(args.run);
  const std::shared_ptr<const Skill> skill = load_skill(args.run, networks.bytes, networks.source, "", args.settings);
  // The episodes training would have evaluated (control/episodes.hpp).
  EpisodeOptions episodes = training_episodes(args.run);
  episodes.episodes = args.episodes, episodes.seed = args.seed, episodes.deterministic = !args.stochastic;
  const bool fixed = !args.fixed_action.empty();
  if (fixed) {
    if (!args.clip.empty() || !args.masses.empty() || !args.switches.empty() || args.latency || !args.transitions.empty() ||
        !args.steering.empty() || args.crossing)
      throw Error("--fixed-action measures the episodes only: give it without --clip, --robustness, --switch, --latency, --transitions, "
                  "--steering and --crossing");
    episodes.fixed_action = Eigen::Map<const Eigen::VectorXd>(args.fixed_action.data(), static_cast<Eigen::Index>(args.fixed_action.size()));
  }
  std::mt19937_64 noise(args.seed);
  EpisodeStats s;
  // Paired: each episode in an environment of its own, in groups of at most kPairedGroup side by
  // side (group g seeded seed + g), so that episode k's start is the same whatever the policy does
  // and memory stays bounded however many episodes are asked for. Its return is the sum of its
  // environment's rewards, listed in episode order.
  std::vector<double> paired_returns;
  if (args.paired) {
    constexpr int kPairedGroup = 32;
    for (int first = 0, group = 0; first < args.episodes; first += kPairedGroup, ++group) {
      EpisodeOptions o = episodes;
      o.episodes = o.slots = std::min(kPairedGroup, args.episodes - first);
      o.seed = args.seed + static_cast<std::uint64_t>(group);
      const Rollout steps = run_episodes(*skill, o, noise, s);
      for (const std::vector<int>& idx : steps.env_steps) {
        double sum = 0.0;
        for (const int i : idx) sum += steps.env_reward[static_cast<std::size_t>(i)];
        paired_returns.push_back(sum);
      }
    }
  } else {
    (void)run_episodes(*skill, episodes, noise, s);
  }
  const std::vector<double> lengths(s.lengths.begin(), s.lengths.end());
  // Episodes ended by a failure: a fall, or a tracking env's max_drift (the JSON's key predates it).
  const double fall_rate = static_cast<double>(s.failures) / static_cast<double>(s.returns.size());
  const std::string actions = fixed ? "fixed " + fmt::format("{}", fmt::join(args.fixed_action, ",")) : args.stochastic ? "sampled" : "mean";
  spdlog::info("{}", args.run.string());
  for (const std::string& setting : args.settings) spdlog::info("  --set           {} (the run's config.yaml is unchanged)", setting);
  spdlog::info("  episodes        {} ({} actions): return {:.2f} +- {:.2f}, length {:.1f} steps, failure rate {:.2f}", s.returns.size(),
               actions, mean_of(s.returns), std_of(s.returns), mean_of(lengths), fall_rate);
  std::string settings;
  for (const std::string& setting : args.settings) settings += (settings.empty() ? "" : ", ") + json_string(setting);
  std::string json = fmt::format("{{\"run\": {}, \"settings\": [{}], \"episodes\": {}, \"actions\": \"{}\", \"return_mean\": {}, "
                                 "\"return_std\": {}, \"episode_length\": {}, \"fall_rate\": {}",
                                 json_string(args.run.string()), settings, s.returns.size(), actions, mean_of(s.returns), std_of(s.returns),
                                 mean_of(lengths), fall_rate);
  if (args.paired) json += ", \"paired\": true, \"returns\": " + json_numbers(paired_returns);
  if (fixed) {
    spdlog::info("  (a baseline: every action the one given, not the policy's; the other measurements are the policy's and are not made)");
    if (!args.json.empty()) write_file_atomic(args.json, json + "}\n");
    return;
  }

  // Imitation: a character environment and a clip to compare with. A behaviour-context env is
  // measured through the env it wraps, the policy's input given the held context's one-hot.
  // Every measurement runs the torch-free runtime (docs/runtime.md), as an embedding program
  // would: the same networks, to within 1.2e-6 of LibTorch's actions.
  const std::unique_ptr<Env> env = make_skill_env(*skill);
  CharacterEnv* character = character_of(*env);
  const bool contexts = dynamic_cast<ContextEnv*>(env.get()) != nullptr;
  if (args.context >= 0 && !contexts) throw Error(args.run.string() + ": --context: this run's environment has no behaviour context");
  std::unique_ptr<Clip> clip;
  if (!args.clip.empty()) {
    if (!character) throw Error(args.run.string() + ": --clip needs a character environment; this run's has no simulated character");
    LoadOptions load;
    load.character = args.character;
    clip = std::make_unique<Clip>(load_motion(args.clip, load));
  }
  // Without --clip: the environment's reference, or else the one clip the skill's starts come
  // from (an adversarial skill draws its starts from its clip and tracks none).
  std::shared_ptr<const Clip> own_clip;
  std::vector<std::shared_ptr<const Clip>> own_clips;
  if (character && !clip && !character->reference() && !contexts) {
    own_clips = skill_clips(*skill);
    if (own_clips.size() == 1) own_clip = own_clips.front();
  }
  const Clip* against = clip ? clip.get() : own_clip.get();
  if (character && (against || character->reference())) {
    const int history = skill->history();
    const PolicyFunction act = policy_on_character(args, skill, *env);
    const ImitationReport r = measure_imitation(*character, act, history, args.trials, against, args.goal_along_clip);
    const std::string name = against ? against->name : character->reference()->name;
    spdlog::info("  imitation       {} trials from evenly spaced phases of '{}', one cycle of {:.2f} s each (mean actions{}{})",
                 r.trial_errors.size(), name, r.cycle_seconds, contexts ? fmt::format(", context {} held", args.context) : "",
                 args.goal_along_clip ? ", commanded along the clip's path" : "");
    spdlog::info("  error           {:.3f} +- {:.3f} m (mean over links of the world position error); per trial: median {:.3f}, "
                 "largest {:.3f} m", r.error_mean(), r.error_std(), median_of(r.trial_errors),
                 *std::max_element(r.trial_errors.begin(), r.trial_errors.end()));
    spdlog::info("  pose error      {:.3f} +- {:.3f} m (the same with the root's offset taken out: posture, not place)",
                 r.pose_error_mean(), r.pose_error_std());
    spdlog::info("  largest links   {}", largest_links(r, r.link_errors, 5));
    spdlog::info("  in posture      {}", largest_links(r, r.link_pose_errors, 5));
    spdlog::info("  falls           {} of {} full episodes; down (a fall, or the root below half the reference's for {} frames) {}", r.falls,
                 r.trial_errors.size(), kLyingFrames, r.down);
    if (!r.trial_returns.empty()) spdlog::info("  normalised return {:.3f} (full episodes; 1 = perfect tracking)", r.normalised_return_mean());
    if (!r.trial_progress.empty())
      spdlog::info("  progress        {:.3f} of the reference's ground covered (full episodes, {} trials; 1 = kept pace)", r.progress_mean(),
                   r.trial_progress.size());
    json += fmt::format(", \"imitation\": {{\"clip\": {}, \"trials\": {}, \"cycle_seconds\": {}, \"error_mean\": {}, \"error_std\": {}, "
                        "\"trial_errors\": {}, \"falls\": {}, \"down\": {}, \"normalised_return\": {}, \"progress\": {}, "
                        "\"trial_progress\": {}, \"pose_error_mean\": {}, \"pose_error_std\": {}, \"trial_pose_errors\": {}, "
                        "\"link_errors\": {}, \"link_pose_errors\": {}, \"step_errors\": {}, \"step_pose_errors\": {}{}{}}}",
                        json_string(name), r.trial_errors.size(), r.cycle_seconds, json_number(r.error_mean()),
                        json_number(r.error_std()), json_numbers(r.trial_errors), r.falls, r.down,
                        json_number(r.normalised_return_mean()), json_number(r.progress_mean()), json_numbers(r.trial_progress),
                        json_number(r.pose_error_mean()), json_number(r.pose_error_std()), json_numbers(r.trial_pose_errors),
                        links_json(r, r.link_errors), links_json(r, r.link_pose_errors), json_numbers(r.step_errors), json_numbers(r.step_pose_errors),
                        contexts ? fmt::format(", \"context\": {}", args.context) : "",
                        args.goal_along_clip ? ", \"goal_along_clip\": true" : "");
  } else if (character && own_clips.size() > 1) {
    std::string names;
    for (const auto& c : own_clips) names += (names.empty() ? "'" : ", '") + c->name + "'";
    spdlog::info("  imitation       not measured: the skill imitates {} clips ({}); give one with --clip", own_clips.size(), names);
  } else if (character) {
    spdlog::info("  imitation       not measured: the environment has no reference clip (give one with --clip)");
  }
  if (!args.masses.empty()) json += robustness(args, networks);
  if (!args.switches.empty()) json += context_switches(args, skill);
  if (args.latency) json += latency(args, skill);
  if (!args.recover.empty()) json += recovery(args);
  if (!args.transitions.empty()) json += transitions(args, run_skill(args.run, args.settings, /*discriminators=*/true));
  if (!args.steering.empty()) json += steering(args);
  if (args.crossing) json += crossing(args);
  if (!args.json.empty()) write_file_atomic(args.json, json + "}\n");
}


void add_eval_command(CLI::App& app) {
  auto args = std::make_shared<EvalArgs>();
  CLI::App* ev = app.add_subcommand("eval", "evaluate a trained policy: return, length, falls and, against a clip, imitation error");
  ev->add_option("run", args->run, "training run directory")->required()->check(CLI::ExistingDirectory);
  ev->add_option("--episodes", args->episodes, "episodes for return, length and fall rate")->capture_default_str()->check(CLI::PositiveNumber);
  ev->add_option("--trials", args->trials, "imitation trials, started at evenly spaced phases of the clip")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  ev->add_option("--clip", args->clip, "reference clip for the imitation error (default: the environment's own)")->check(CLI::ExistingFile);
  ev->add_option("--character", args->character, "DeepMimic character file of a .txt --clip (default: found by its name)");
  ev->add_option("--context", args->context, "behaviour context held in the imitation trials (a run with env.context)")
      ->check(CLI::NonNegativeNumber);
  ev->add_option("--robustness", args->masses, "projectile masses (kg) for seed 004's robustness test, e.g. 0,1,5,10,20 (0: no cubes, the control)")
      ->delimiter(',')
      ->check(CLI::NonNegativeNumber);
  ev->add_option("--robustness-trials", args->robustness_trials, "trials per mass (seed 004: 1,000)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  ev->add_option("--robustness-seconds", args->robustness_seconds, "longest trial (s)")->capture_default_str()->check(CLI::PositiveNumber);
  ev->add_option("--switch", args->switches, "behaviour contexts, e.g. 0,1: measure the switch between every ordered pair (a run with env.context)")
      ->delimiter(',')
      ->check(CLI::NonNegativeNumber);
  ev->add_option("--switch-seconds", args->switch_seconds, "how long each context of a switch is held")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  ev->add_option("--transitions", args->transitions,
                 "other skills of the same character (model directories): seed 004's transition test between every ordered pair "
                 "(the rules of --transition-rules at each tau of --transition-taus)")
      ->delimiter(',')
      ->check(CLI::ExistingDirectory);
  ev->add_option("--transition-trials", args->transition_trials, "trials per pair, rule and tau")->capture_default_str()->check(CLI::PositiveNumber);
  ev->add_option("--transition-rules", args->transition_rules,
                 "score (seed 004: the target's discriminators), value (the target's value over its own mean), matching (pose to the "
                 "target clip's nearest frame), immediately")
      ->delimiter(',')
      ->capture_default_str()
      ->check(CLI::IsMember({"score", "value", "matching", "immediately"}));
  ev->add_option("--transition-taus", args->transition_taus, "the thresholds tau of the score, value and matching rules (default -0.6,-0.4,...,1)")
      ->delimiter(',');
  ev->add_option("--recover", args->recover,
                 "get-up skills (model directories) for robustness with recovery: at each --robustness mass, the fraction of "
                 "--robustness-seconds spent performing without and with them (seed 004 section 6)")
      ->delimiter(',')
      ->check(CLI::ExistingDirectory);
  ev->add_option("--recover-tau", args->recover_tau, "the score at which the skill takes the character back from a get-up that is done (its clip's duration with the character, and up); -1: at once then (the walk rates a character standing still -0.4 to -0.5)")
      ->capture_default_str();
  ev->add_option("--steering", args->steering, "commanded turns in degrees, e.g. 45,90: how a skill with a heading goal (env.goal: heading) turns")
      ->delimiter(',')
      ->check(CLI::Range(0.0, 180.0));
  ev->add_option("--steering-trials", args->steering_trials, "trials per turn")->capture_default_str()->check(CLI::PositiveNumber);
  ev->add_flag("--goal-along-clip", args->goal_along_clip,
               "imitation trials of a skill with a heading goal: command at every step the clip's direction of travel (its root's over "
               "a cycle centred on the moment), so that it walks the clip's own path (default: the target is drawn as in training)");
  ev->add_flag("--crossing", args->crossing,
              "how often the skill gets over its course (the run's env.terrain, or one given by --set \"env.terrain={kind: stairs, "
              "step_height: 0.1}\"); a skill with a heading goal is commanded along it");
  ev->add_option("--crossing-trials", args->crossing_trials, "trials over the course")->capture_default_str()->check(CLI::PositiveNumber);
  ev->add_option("--crossing-seconds", args->crossing_seconds, "the longest trial (s)")->capture_default_str()->check(CLI::PositiveNumber);
  ev->add_option("--fixed-action", args->fixed_action,
                 "a baseline: the episodes (only they) with this action in place of the policy's, e.g. 0 for a navigation "
                 "controller's straight on; with --paired, episode k has the same start and course as the policy's")
      ->delimiter(',');
  ev->add_flag("--paired", args->paired,
              "each episode in its own environment, so that episode k starts the same (on the same course) whatever the policy does, "
              "for the same --episodes and --seed; "
              "the JSON lists the returns in episode order, to compare two evaluations episode by episode");
  ev->add_flag("--latency", args->latency, "time one policy forward pass at batch 1 (seed 004 Table 4)");
  ev->add_flag("--stochastic", args->stochastic, "sample actions in the episodes (default: the policy's mean)");
  ev->add_option("--seed", args->seed, "random seed of the episodes")->capture_default_str();
  ev->add_option("--json", args->json, "also write the figures to this JSON file");
  ev->add_option("--set", args->settings,
                 "override an environment key of the run's config for this evaluation: env.KEY=VALUE (e.g. env.start_momentum_window=0.1); "
                 "repeatable");
  ev->callback([args] { evaluate(*args); });
}

}  // namespace mimic::app
