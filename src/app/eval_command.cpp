// mimic eval RUN: one measurement for every policy (DESIGN.md section 5): episode return, length
// and fall rate; for a character with a reference clip (the env's own, or --clip), the imitation
// error over one cycle from evenly spaced phases and the normalised return. A table on the
// terminal, and the same figures as JSON with --json.
#include <spdlog/spdlog.h>

#include <cmath>
#include <numeric>

#include "app/commands.hpp"
#include "core/error.hpp"
#include "core/file_io.hpp"
#include "env/character_env.hpp"
#include "learn/imitation_eval.hpp"
#include "learn/trainer.hpp"

namespace mimic::app {

namespace {

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

// JSON has no NaN: unknown figures are null.
std::string json_number(double v) { return std::isfinite(v) ? fmt::format("{}", v) : "null"; }

double mean(const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size()); }
double stddev(const std::vector<double>& v) {
  const double m = mean(v);
  double s = 0;
  for (double x : v) s += (x - m) * (x - m);
  return std::sqrt(s / static_cast<double>(v.size()));
}

struct EvalArgs {
  std::filesystem::path run, json, clip, character;
  int episodes = 20, trials = 20;
  bool stochastic = false;
  std::uint64_t seed = 12345;
};

void evaluate(const EvalArgs& args) {
  const std::unique_ptr<Trainer> trainer = Trainer::load_policy(args.run);
  const EpisodeStats s = trainer->run_episodes(args.episodes, args.seed, !args.stochastic);
  const std::vector<double> lengths(s.lengths.begin(), s.lengths.end());
  const double fall_rate = static_cast<double>(s.failures) / static_cast<double>(s.returns.size());
  const char* actions = args.stochastic ? "sampled" : "mean";
  spdlog::info("{}", args.run.string());
  spdlog::info("  episodes        {} ({} actions): return {:.2f} +- {:.2f}, length {:.1f} steps, fall rate {:.2f}", s.returns.size(),
               actions, mean(s.returns), stddev(s.returns), mean(lengths), fall_rate);
  std::string json = fmt::format("{{\"run\": {}, \"episodes\": {}, \"actions\": \"{}\", \"return_mean\": {}, \"return_std\": {}, "
                                 "\"episode_length\": {}, \"fall_rate\": {}",
                                 json_string(args.run.string()), s.returns.size(), actions, mean(s.returns), stddev(s.returns),
                                 mean(lengths), fall_rate);

  // Imitation: a character environment and a clip to compare with.
  const std::unique_ptr<Env> env = trainer->make_env();
  auto* character = dynamic_cast<CharacterEnv*>(env.get());
  std::unique_ptr<Clip> clip;
  if (!args.clip.empty()) {
    if (!character) throw Error(args.run.string() + ": --clip needs a character environment; this run's has no simulated character");
    LoadOptions load;
    load.character = args.character;
    clip = std::make_unique<Clip>(load_motion(args.clip, load));
  }
  if (character && (clip || character->reference())) {
    const int history = trainer->config().policy.net.history;
    const PolicyFunction act = [&](const Eigen::VectorXd& input) { return trainer->act(input); };
    const ImitationReport r = measure_imitation(*character, act, history, args.trials, clip.get());
    const std::string name = clip ? clip->name : character->reference()->name;
    spdlog::info("  imitation       {} trials from evenly spaced phases of '{}', one cycle of {:.2f} s each (mean actions)",
                 r.trial_errors.size(), name, r.cycle_seconds);
    spdlog::info("  error           {:.3f} +- {:.3f} m (mean over links of the world position error)", r.error_mean(), r.error_std());
    spdlog::info("  falls           {} of {} full episodes", r.falls, r.trial_errors.size());
    if (!r.trial_returns.empty()) spdlog::info("  normalised return {:.3f} (full episodes; 1 = perfect tracking)", r.normalised_return_mean());
    json += fmt::format(", \"imitation\": {{\"clip\": {}, \"trials\": {}, \"cycle_seconds\": {}, \"error_mean\": {}, \"error_std\": {}, "
                        "\"falls\": {}, \"normalised_return\": {}}}",
                        json_string(name), r.trial_errors.size(), r.cycle_seconds, json_number(r.error_mean()),
                        json_number(r.error_std()), r.falls, json_number(r.normalised_return_mean()));
  } else if (character) {
    spdlog::info("  imitation       not measured: the environment has no reference clip (give one with --clip)");
  }
  if (!args.json.empty()) write_file_atomic(args.json, json + "}\n");
}

}  // namespace

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
  ev->add_flag("--stochastic", args->stochastic, "sample actions in the episodes (default: the policy's mean)");
  ev->add_option("--seed", args->seed, "random seed of the episodes")->capture_default_str();
  ev->add_option("--json", args->json, "also write the figures to this JSON file");
  ev->callback([args] { evaluate(*args); });
}

}  // namespace mimic::app
