// mimic distill CONFIG --teacher RUN... -o OUT: several single-skill policies become one that
// switches on a behaviour context (DAgger; learn/imitation/distillation.hpp). The result is a run directory
// like any other (config.yaml + checkpoint.pt): mimic eval, render, export, and mimic train
// --init-from OUT to fine-tune it with the config's rewards.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <sstream>

#include "app/commands.hpp"
#include "app/stop_requests.hpp"
#include "app/run_skill.hpp"
#include "core/config_file.hpp"
#include "core/error.hpp"
#include "core/file_io.hpp"
#include "env/context_env.hpp"
#include "learn/imitation/distillation.hpp"
#include "learn/trainer/trainer.hpp"

namespace mimic::app {

namespace {

constexpr const char* kHeader = "round,samples,kept,episode_length,episode_return,falls,loss,wall_s";

// The rows of OUT/distill.csv so far (header first), and the last row's round, samples and wall time.
struct Progress {
  std::string text;
  int round = 0;
  long long samples = 0;
  double wall_s = 0;
};

Progress read_progress(const std::filesystem::path& csv) {
  Progress p;
  p.text = std::string(kHeader) + "\n";
  if (!std::filesystem::exists(csv)) return p;
  std::ifstream in(csv);
  std::string line;
  if (!std::getline(in, line) || line != kHeader) throw Error(csv.string() + ": line 1 is not distill.csv's header (" + kHeader + ")");
  for (int n = 2; std::getline(in, line); ++n) {
    if (line.empty()) continue;
    std::istringstream row(line);
    std::string cell;
    std::vector<std::string> cells;
    while (std::getline(row, cell, ',')) cells.push_back(cell);
    try {
      if (cells.size() != 8) throw std::invalid_argument("cells");
      p.round = std::stoi(cells[0]), p.samples = std::stoll(cells[1]), p.wall_s = std::stod(cells[7]);
    } catch (const std::exception&) {
      throw Error(csv.string() + ": line " + std::to_string(n) + " is not a row of 8 numbers");
    }
    p.text += line + "\n";
  }
  return p;
}

}  // namespace

void add_distill_command(CLI::App& app) {
  struct Args {
    std::filesystem::path config, out;
    std::vector<std::filesystem::path> teachers;
    std::vector<std::string> settings;
    DistillOptions o;
    int threads = -1;
    bool resume = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand(
      "distill", "one policy from several: the student acts, teacher k labels its states under behaviour context k (DAgger)");
  cmd->add_option("config", args->config,
                  "the student's training config (.yaml): environment with env.context (one context per teacher) and policy; "
                  "with --resume, OUT/config.yaml")
      ->check(CLI::ExistingFile);
  cmd->add_option("--teacher", args->teachers, "a trained run or model per context, in context order (repeat it)")
      ->required()
      ->check(CLI::ExistingDirectory);
  cmd->add_option("-o,--out", args->out, "run directory to write (config.yaml, checkpoint.pt after every round, distill.csv)")->required();
  cmd->add_flag("--resume", args->resume, "go on from OUT's checkpoint and distill.csv (the kept states start empty)");
  cmd->add_option("--rounds", args->o.rounds, "rounds in all (each: student episodes, labels, regression)")->capture_default_str()->check(CLI::PositiveNumber);
  cmd->add_option("--episodes", args->o.episodes, "student episodes per round")->capture_default_str()->check(CLI::PositiveNumber);
  cmd->add_option("--keep", args->o.keep, "labelled states kept, the newest")->capture_default_str()->check(CLI::PositiveNumber);
  cmd->add_option("--epochs", args->o.epochs, "passes over the kept states per round")->capture_default_str()->check(CLI::PositiveNumber);
  cmd->add_option("--lr", args->o.lr, "Adam learning rate")->capture_default_str()->check(CLI::PositiveNumber);
  cmd->add_option("--batch", args->o.batch, "minibatch size")->capture_default_str()->check(CLI::PositiveNumber);
  cmd->add_option("--seed", args->o.seed, "random seed (starts, action noise, minibatches)")->capture_default_str();
  cmd->add_option("--threads", args->threads, "override collect.threads for the student's episodes (0: every core)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--set", args->settings, "override a config value: KEY.PATH=VALUE (repeatable)");
  cmd->callback([args] {
    const std::filesystem::path checkpoint = args->out / "checkpoint.pt", csv = args->out / "distill.csv";
    if (!args->resume && std::filesystem::exists(checkpoint))
      throw Error(args->out.string() + " already holds a run (checkpoint.pt): pass --resume to go on with it, or choose another directory");
    if (args->resume && !std::filesystem::exists(checkpoint)) throw Error(checkpoint.string() + ": no checkpoint to resume from");
    // A resumed student goes on under the config it was started with (its noise, its networks).
    if (args->resume && (!args->config.empty() || !args->settings.empty()))
      throw Error("distill --resume goes on with " + (args->out / "config.yaml").string() + ": give neither a config nor --set");
    if (!args->resume && args->config.empty()) throw Error("distill: the student's config is needed (or --resume -o OUT)");
    // The student learns from its teachers, not from rewards: its run must load without the
    // config's expert files, and a later `mimic train --init-from` brings the rewards it wants.
    std::vector<std::string> settings = args->settings;
    if (!args->resume) settings.push_back("rewards=[{source: env}]");
    const std::filesystem::path config = args->resume ? args->out / "config.yaml" : args->config;
    const std::string source = config.string();
    const std::string text = override_config(read_config_file(config), source, settings);
    TrainConfig cfg = parse_train_config(text, source);
    if (args->threads >= 0) cfg.collect.threads = resolve_threads(args->threads);
    if (cfg.policy.net.history != 1) throw Error(source + ": distillation needs a student that sees one frame (policy.history: 1)");
    Trainer student(cfg);
    Progress progress;
    if (args->resume) {
      student.load_checkpoint(checkpoint);
      progress = read_progress(csv);
    } else {
      progress = read_progress({});
    }
    // Teacher k sees the student's frame without the one-hot.
    const std::optional<ObservationSlice> context = context_slice(student.observation_layout());
    const int context_width = context ? context->size : 0;
    if (static_cast<int>(args->teachers.size()) != std::max(context_width, 1))
      throw Error(std::to_string(args->teachers.size()) + " teachers for " + source + "'s " +
                  (context_width ? std::to_string(context_width) + " behaviour contexts: give one --teacher per context, in context order"
                                 : std::string("environment without behaviour contexts: give one --teacher (or add env.context)")));
    // The teachers act on the runtime (control/), as exported.
    std::vector<PolicyFunction> acts;
    for (const auto& path : args->teachers) {
      const std::shared_ptr<const Skill> t = run_skill(path);
      if (t->history() != 1) throw Error(path.string() + ": a teacher must see one frame (policy.history: 1)");
      if (t->input_size() != student.input_size() - context_width || t->action_size() != student.action_size())
        throw Error(path.string() + ": the teacher takes " + std::to_string(t->input_size()) + " observation values and gives " +
                    std::to_string(t->action_size()) + " actions; the student's environment (" + source + ") has " +
                    std::to_string(student.input_size() - context_width) + " without its context and " +
                    std::to_string(student.action_size()) + " actions");
      acts.push_back([t](const Eigen::VectorXd& input) { return t->act(input); });
    }
    std::filesystem::create_directories(args->out);
    if (!args->resume) write_file_atomic(args->out / "config.yaml", "# mimic distill: the student's config, learnt from its teachers\n" + text);
    DistillOptions o = args->o;
    o.first_round = progress.round + 1;
    o.samples_before = progress.samples;
    if (o.first_round > o.rounds) {
      spdlog::info("{}: all {} rounds done", args->out.string(), o.rounds);
      return;
    }
    spdlog::info("distilling {} teacher{} into {} (rounds {} to {}, {} student episodes each, {} threads)", acts.size(),
                 acts.size() == 1 ? "" : "s", args->out.string(), o.first_round, o.rounds, o.episodes, cfg.collect.threads);
    handle_stop_signals();
    const auto start = std::chrono::steady_clock::now();
    distill(student, acts, o, [&](const DistillRound& r) {
      const double wall = progress.wall_s + std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      student.save_checkpoint(checkpoint);
      progress.text += fmt::format("{},{},{},{},{},{},{},{:.1f}\n", r.round, r.samples, r.kept, r.episode_length, r.episode_return, r.falls,
                                   r.loss, wall);
      write_file_atomic(csv, progress.text);
      spdlog::info("round {:>4}  samples {:>9}  kept {:>6}  episodes {:.0f} steps, {} of {} fell  loss {:.5f}  {:.0f} s", r.round, r.samples,
                   r.kept, r.episode_length, r.falls, o.episodes, r.loss, wall);
      return stop_requests() == 0;
    });
    spdlog::info("{}; checkpoint {}", stop_requests() > 0 ? "stopped" : "done", checkpoint.string());
  });
}

}  // namespace mimic::app
