// mimic train CONFIG.yaml [-o RUN] [--resume] (or --resume -o RUN); mimic export RUN -o MODEL; mimic bench train
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "app/commands.hpp"
#include "app/run_data.hpp"
#include "app/stop_requests.hpp"
#include "core/config_file.hpp"
#include "core/error.hpp"
#include "core/file_io.hpp"
#include "learn/networks/runtime_format.hpp"
#include "learn/trainer/ranks.hpp"
#include "learn/trainer/train_bench.hpp"
#include "learn/trainer/trainer.hpp"

namespace mimic::app {

namespace {

std::string join_names(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

std::string cell(const IterationMetrics& m, const char* name, const char* format) {
  const double v = m.get(name);
  return std::isfinite(v) ? fmt::format(fmt::runtime(format), v) : std::string("-");
}

}  // namespace

void add_train_commands(CLI::App& app) {
  struct Args {
    std::filesystem::path config, out, bench_config, init_from;
    std::vector<std::filesystem::path> init_discriminators_from;
    bool resume = false;
    int iterations = 0, threads = -1;
    std::vector<std::string> settings;
    TrainBenchOptions bench;
  };
  auto args = std::make_shared<Args>();
  CLI::App* train = app.add_subcommand("train", "train a policy with PPO from a YAML config (see docs/training.md)");
  train->add_option("config", args->config, "training config (.yaml); with --resume, default RUN/config.yaml")->check(CLI::ExistingFile);
  train->add_option("-o,--out", args->out, "run directory (default: runs/<config name>)");
  train->add_flag("--resume", args->resume, "continue the run in the run directory from its checkpoint");
  train->add_option("--init-from", args->init_from,
                    "start a new run from another run's weights (RUN or a checkpoint; an exported model too): policy, value, normalisers, "
                    "discriminators; fresh optimisers and counters")
      ->check(CLI::ExistingPath)
      ->excludes("--resume");
  train->add_option("--init-discriminators-from", args->init_discriminators_from,
                    "start each behaviour context's discriminator (a reward source with per_context) from its own run or model on that "
                    "behaviour alone: one per context, in context order (after --init-from, whose discriminator they replace)")
      ->check(CLI::ExistingPath)
      ->excludes("--resume");
  train->add_option("--iterations", args->iterations, "override the config's iteration count (kept in RUN/config.yaml)")->check(CLI::PositiveNumber);
  train->add_option("--threads", args->threads, "override collect.threads (0: every core)")->check(CLI::NonNegativeNumber);
  train->add_option("--set", args->settings, "override a config value: KEY.PATH=VALUE (e.g. ppo.clip=0.1, rewards.0.episodes=10); repeatable");
  train->callback([args] {
    if (args->resume && !args->settings.empty()) throw Error("--set: a resumed run keeps the config it was started with");
    if (args->config.empty()) {
      if (!args->resume || args->out.empty()) throw Error("train: a config is needed (or --resume -o RUN, which goes on with RUN/config.yaml)");
      args->config = args->out / "config.yaml";
    }
    const std::string source = args->config.string();
    TrainConfig cfg = parse_train_config(override_config(read_config_file(args->config), source, args->settings), source);
    if (args->iterations > 0) cfg.iterations = args->iterations;  // the Trainer records it in RUN/config.yaml
    if (args->threads >= 0) cfg.collect.threads = resolve_threads(args->threads);
    TrainOptions opts;
    opts.run_dir = args->out.empty() ? std::filesystem::path("runs") / args->config.stem() : args->out;
    opts.resume = args->resume;
    opts.init_from = args->init_from;
    opts.init_discriminators_from = args->init_discriminators_from;
    opts.stop_requests = stop_requests;
    opts.on_iteration = [](const IterationMetrics& m) {
      spdlog::info("iter {:>5}  samples {:>9}  return {:>9}  len {:>6}  kl {:>8}  ent {:>7}  ev {:>6}  {:>7} samples/s",
                   m.iteration, cell(m, "samples", "{:.0f}"), cell(m, "return", "{:.2f}"), cell(m, "episode_length", "{:.0f}"),
                   cell(m, "kl", "{:.4f}"), cell(m, "entropy", "{:.2f}"), cell(m, "explained_variance", "{:.2f}"),
                   cell(m, "samples_per_s", "{:.0f}"));
    };
    handle_stop_signals();
    Trainer trainer(cfg, opts);
    spdlog::info("{} {} in {} ({} envs, {} threads, {} samples per iteration, input {}, actions {})",
                 args->resume ? "resuming at iteration" : "training from iteration", trainer.iteration(), opts.run_dir.string(),
                 cfg.collect.envs, cfg.collect.threads, cfg.collect.samples, trainer.input_size(), trainer.action_size());
    if (ranks::many())
      spdlog::info("{} ranks (mpirun): each collects {} samples an iteration with its own {} environments ({} in all); gradients, normalisers "
                   "and discriminator updates are combined every step",
                   ranks::size(), cfg.collect.samples, cfg.collect.envs, static_cast<long long>(cfg.collect.samples) * ranks::size());
    if (args->resume && trainer.saved_ranks() != ranks::size())
      spdlog::warn("{} was saved by {} rank(s) and goes on over {}: networks, optimisers and normalisers carry on; each iteration now has {} "
                   "times the samples, and ranks the checkpoint does not hold start fresh generators",
                   (opts.run_dir / "checkpoint.pt").string(), trainer.saved_ranks(), ranks::size(),
                   fmt::format("{:.3g}", static_cast<double>(ranks::size()) / trainer.saved_ranks()));
    if (!args->init_from.empty())
      spdlog::info("weights from {}: policy, value, normalisers and {} of {} reward sources' state{}", args->init_from.string(),
                   trainer.reward_sources_initialised(), cfg.rewards.size(),
                   cfg.policy.learn_std ? "" : fmt::format("; action noise held at the config's log_std {}", cfg.policy.log_std));
    for (std::size_t k = 0; k < args->init_discriminators_from.size(); ++k)
      spdlog::info("context {}'s discriminator from {}", k, args->init_discriminators_from[k].string());
    if (trainer.contexts_added_by_init() > 0)
      spdlog::info("{} had no behaviour context: its inputs were widened by the {}-context one-hot, whose weights start at zero "
                   "(every context acts as it did)",
                   args->init_from.string(), trainer.contexts_added_by_init());
    if (!trainer.parts_added_by_init().empty())
      spdlog::info("{} was saved without the observation parts {}: its inputs were widened by them, with weights starting at zero "
                   "(the policy acts as it did until it learns to use them)",
                   args->init_from.string(), join_names(trainer.parts_added_by_init()));
    const RunEnd end = trainer.run();
    if (end.stopped) {
      spdlog::info("stop requested{}: saved iteration {}, the last completed ({} samples), to {}; mimic train --resume -o {} goes on from it",
                   end.interrupted.empty() ? "" : " (" + end.interrupted + ")", end.iteration, trainer.samples(),
                   (opts.run_dir / "checkpoint.pt").string(), opts.run_dir.string());
    } else {
      release_stop_signals();
      spdlog::info("done after {} iterations ({} samples); checkpoint {}", end.iteration, trainer.samples(),
                   (opts.run_dir / "checkpoint.pt").string());
    }
  });

  // A run's checkpoint keeps everything training needs to go on (tens of MB for an imitation run:
  // Adam moments, the discriminator's replay); a model to commit or ship needs only what acts.
  struct ExportArgs {
    std::filesystem::path run, out;
    std::vector<std::filesystem::path> average_with;
    int average_last = 0;
    std::filesystem::path policy_from;
    bool networks_only = false;
  };
  auto exp = std::make_shared<ExportArgs>();
  CLI::App* export_cmd = app.add_subcommand(
      "export", "an acting-only copy of a run (config.yaml, a slim checkpoint.pt, metrics.csv): for models/, eval, render, embedding");
  export_cmd->add_option("run", exp->run, "training run directory (config.yaml + checkpoint.pt)")->required()->check(CLI::ExistingDirectory);
  export_cmd->add_option("-o,--out", exp->out, "model directory to write")->required();
  export_cmd->add_option("--average-with", exp->average_with,
                         "other checkpoints of the run (directories or checkpoint files, e.g. copies taken as it trained): the model's "
                         "policy weights are the mean of these and the run's own; the run's normalisers, value and discriminators are kept")
      ->check(CLI::ExistingPath);
  export_cmd->add_option("--average-last", exp->average_last,
                         "the model's policy weights are the mean of the run's last K: its own and the K-1 policy snapshots before it "
                         "(RUN/snapshots, written with the config's snapshot_every)")
      ->check(CLI::Range(2, 1'000'000));
  export_cmd->add_option("--policy-from", exp->policy_from,
                         "the policy as it was in this snapshot or checkpoint of the run (e.g. RUN/snapshots/000400.pt): its weights, "
                         "normaliser and iteration; the run's value and discriminators are kept")
      ->check(CLI::ExistingPath)
      ->excludes("--average-with")
      ->excludes("--average-last");
  export_cmd->add_flag("--networks-only", exp->networks_only,
                       "write only OUT/networks.mimic, the torch-free runtime's networks (docs/runtime.md), e.g. into an existing "
                       "model directory (OUT may be RUN)")
      ->excludes("--average-with")
      ->excludes("--average-last")
      ->excludes("--policy-from");
  export_cmd->callback([exp] {
    if (exp->networks_only) {
      // With the discriminators where their expert files are found (scores, switching by score).
      std::unique_ptr<Trainer> trainer;
      try {
        trainer = Trainer::from_run(exp->run, true);
      } catch (const Error& e) {
        trainer = Trainer::from_run(exp->run);
        spdlog::warn("{}: the networks are written without the discriminators: {}", exp->run.string(), e.what());
      }
      std::filesystem::create_directories(exp->out);
      trainer->write_runtime_networks(exp->out / kRuntimeFileName);
      spdlog::info("wrote {} ({:.2f} MB), iteration {}", (exp->out / kRuntimeFileName).string(),
                   static_cast<double>(std::filesystem::file_size(exp->out / kRuntimeFileName)) / 1e6, trainer->iteration());
      return;
    }
    if (std::filesystem::exists(exp->out / "checkpoint.pt"))
      throw Error(exp->out.string() + " already holds a checkpoint.pt: choose another directory or remove it");
    // With its reward sources, so that the discriminators' scores stay available to the model.
    const std::unique_ptr<Trainer> trainer = Trainer::from_run(exp->run, true);
    if (exp->average_last > 0) {
      std::vector<std::filesystem::path> before;
      for (const auto& [iteration, path] : Trainer::policy_snapshots(exp->run))
        if (iteration < trainer->iteration()) before.push_back(path);
      const auto wanted = static_cast<std::size_t>(exp->average_last - 1);
      if (before.size() < wanted)
        throw Error((exp->run / "snapshots").string() + ": " + std::to_string(before.size()) + " policy snapshots before the run's iteration " +
                    std::to_string(trainer->iteration()) + "; --average-last " + std::to_string(exp->average_last) + " needs " +
                    std::to_string(wanted) + " (the config's snapshot_every writes them as the run trains)");
      exp->average_with.insert(exp->average_with.end(), before.end() - static_cast<std::ptrdiff_t>(wanted), before.end());
    }
    std::string provenance;  // the model's config says where its policy comes from
    if (!exp->policy_from.empty()) {
      trainer->take_policy_from(exp->policy_from);
      provenance = "# policy: " + exp->policy_from.string() + " (iteration " + std::to_string(trainer->iteration()) + ")\n";
    }
    if (!exp->average_with.empty()) {
      const double shift = trainer->average_policy_with(exp->average_with);
      spdlog::info("policy weights averaged over {} checkpoints; their observation means lie within {:.3f} standard deviations of the run's",
                   exp->average_with.size() + 1, shift);
      provenance = fmt::format("# policy weights: the mean of this run's at iteration {} and", trainer->iteration());
      for (const auto& p : exp->average_with) provenance += " " + p.string();
      provenance += "\n";
    }
    std::filesystem::create_directories(exp->out);
    // A run of `mimic imitate` names its clips, character and demonstrations from its own directory.
    std::string copied;
    for (const std::string& d : copy_run_data(exp->run, exp->out)) copied += (copied.empty() ? "" : ", ") + d;
    if (!copied.empty()) spdlog::info("copied the run's {} into {}", copied, exp->out.string());
    write_file_atomic(exp->out / "config.yaml", provenance + read_text_file(exp->run / "config.yaml"));
    if (std::filesystem::exists(exp->run / "metrics.csv"))
      write_file_atomic(exp->out / "metrics.csv", read_text_file(exp->run / "metrics.csv"));
    trainer->export_model(exp->out / "checkpoint.pt");
    const auto mb = [](const std::filesystem::path& p) { return static_cast<double>(std::filesystem::file_size(p)) / 1e6; };
    spdlog::info("wrote {} ({:.1f} MB; the run's checkpoint: {:.1f} MB), iteration {}, {} samples", (exp->out / "checkpoint.pt").string(),
                 mb(exp->out / "checkpoint.pt"), mb(exp->run / "checkpoint.pt"), trainer->iteration(), trainer->samples());
  });

  CLI::App* bench = app.add_subcommand("bench", "throughput figures");
  bench->require_subcommand(1);
  add_bench_policy_command(*bench);
  CLI::App* bench_train = bench->add_subcommand(
      "train", "end-to-end training samples/s (the humanoid at seed 004 Table 1 sizes, or --config) beside the simulation-only rate");
  bench_train->add_option("--threads", args->bench.threads, "worker threads (a list: 1,2)")->delimiter(',')->capture_default_str();
  bench_train->add_option("--iterations", args->bench.iterations, "timed iterations after one warm-up")->capture_default_str()->check(CLI::PositiveNumber);
  CLI::Option* samples = bench_train->add_option("--samples", args->bench.samples, "samples per iteration (PPO buffer)")
                             ->capture_default_str()->check(CLI::PositiveNumber);
  bench_train->add_option("--rounds", args->bench.rounds, "measure every setting this many times, one round after another, and report medians")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  bench_train->add_flag("--overlap", args->bench.overlap, "measure each thread count also with collect.overlap (learning beside collection)");
  CLI::Option* envs = bench_train->add_option("--envs", args->bench.envs, "environments")->capture_default_str()->check(CLI::PositiveNumber);
  // A config brings its own samples and environments: the two options would be ignored.
  bench_train->add_option("--config", args->bench_config, "time this training config instead (e.g. an imitation run, discriminator included)")
      ->check(CLI::ExistingFile)->excludes(samples)->excludes(envs);
  bench_train->callback([args] {
    if (!args->bench_config.empty()) {
      args->bench.config_source = args->bench_config.string();
      args->bench.config_text = read_config_file(args->bench_config);
    }
    const std::vector<TrainBenchResult> results = run_train_benchmark(args->bench, [](const std::string& line) { spdlog::info("{}", line); });
    if (ranks::rank() == 0) fmt::print("{}", format_train_benchmark(args->bench, results));
  });
}

}  // namespace mimic::app
