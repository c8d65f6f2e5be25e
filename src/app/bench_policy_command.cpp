// mimic bench policy MODEL [--json F]: the torch-free runtime beside LibTorch on a trained policy
// (batch 1, batch 64, the largest action difference) and a crowd of characters on one core.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "app/commands.hpp"
#include "control/skill_impl.hpp"
#include "env/context_env.hpp"
#include "core/error.hpp"
#include "core/file_io.hpp"
#include "core/stopwatch.hpp"
#include "learn/networks/policy_timing.hpp"
#include "mimic/runtime.hpp"

namespace mimic::app {

namespace {

struct BenchPolicyArgs {
  std::filesystem::path model, json;
  std::vector<int> crowd = {1, 10, 100};
  double seconds = 2.0;
};

// Inputs from the skill's own episodes (restarted where one ends).
Eigen::MatrixXd own_inputs(const std::shared_ptr<const Skill>& skill, int n) {
  Controller c({skill}, 11);
  Eigen::MatrixXd inputs(n, skill->input_size());
  for (int i = 0; i < n; ++i) {
    const StepInfo info = c.step();
    inputs.row(i) = c.last_input().transpose();
    if (info.episode_over) c.reset();
  }
  return inputs;
}

// Control steps per second (summed over the characters) of `n` characters, each its own
// controller stepped in turn on this thread: simulation and inference, as a game's update loop.
// With a `candidate` (the same skill under another name), every controller keeps a request for
// it pending that no state grants: the candidate's discriminators score every step, as a switch
// waiting for its moment does.
double crowd_steps_per_second(const std::shared_ptr<const Skill>& skill, int n, double seconds,
                              const std::shared_ptr<const Skill>& candidate = nullptr) {
  std::vector<std::unique_ptr<Controller>> crowd;
  SwitchRule never;
  never.threshold = 2.0;  // above the score's range
  never.time_limit_seconds = 1e9;
  for (int i = 0; i < n; ++i) {
    std::vector<std::shared_ptr<const Skill>> skills;
    skills.reserve(2);
    skills.push_back(skill);
    if (candidate) skills.push_back(candidate);
    crowd.push_back(std::make_unique<Controller>(skills, static_cast<std::uint64_t>(100 + i)));
    crowd.back()->set_switch_rule(never);
    if (candidate) crowd.back()->request(candidate->name());
  }
  long long steps = 0;
  const Stopwatch clock;
  while (clock.seconds() < seconds)
    for (auto& c : crowd) {
      if (c->step().episode_over) {
        c->reset();
        if (candidate) c->request(candidate->name());
      }
      ++steps;
    }
  return static_cast<double>(steps) / clock.seconds();
}

}  // namespace

void add_bench_policy_command(CLI::App& bench) {
  auto args = std::make_shared<BenchPolicyArgs>();
  CLI::App* cmd = bench.add_subcommand(
      "policy", "a trained policy on the torch-free runtime beside LibTorch (batch 1, batch 64, action difference), and a crowd of characters, on one core");
  cmd->add_option("model", args->model, "model directory (config.yaml, checkpoint.pt, networks.mimic)")->required()->check(CLI::ExistingDirectory);
  cmd->add_option("--json", args->json, "also write the figures here (torch_free_us, libtorch_us, max_action_diff, crowd, ...)");
  cmd->add_option("--crowd", args->crowd, "crowd sizes to time")->delimiter(',')->capture_default_str()->check(CLI::Range(1, 100000));
  cmd->add_option("--seconds", args->seconds, "seconds each figure is timed over")->capture_default_str()->check(CLI::Range(0.01, 3600.0));
  cmd->callback([args] {
    const std::shared_ptr<const Skill> skill = Skill::load(args->model);
    const std::unique_ptr<Trainer> trainer = Trainer::from_run(args->model);
    spdlog::info("{}: policy of {} parameters, {} inputs -> {} actions", skill->name(), skill->policy_parameters(), skill->input_size(),
                 skill->action_size());
    const Eigen::MatrixXd inputs = own_inputs(skill, 1024);
    const Eigen::MatrixXd ours = skill->act(inputs), theirs = libtorch_policy_actions(*trainer, inputs);
    double max_diff = 0, max_relative = 0;
    for (Eigen::Index i = 0; i < inputs.rows(); ++i) {
      const double d = (ours.row(i) - theirs.row(i)).cwiseAbs().maxCoeff();
      max_diff = std::max(max_diff, d);
      max_relative = std::max(max_relative, d / std::max(1.0, theirs.row(i).cwiseAbs().maxCoeff()));
    }
    const auto runtime = [&skill](const Eigen::MatrixXd& b) { return skill->act(b); };
    const double free1 = microseconds_per_batch(inputs, 1, args->seconds, runtime);
    const double torch1 = libtorch_policy_microseconds(*trainer, inputs, 1, args->seconds);
    const double free64 = microseconds_per_batch(inputs, 64, args->seconds, runtime);
    const double torch64 = libtorch_policy_microseconds(*trainer, inputs, 64, args->seconds);
    fmt::print("{}: {} inputs from its own episodes\n", skill->name(), inputs.rows());
    fmt::print("  batch 1:   torch-free {:8.1f} us, LibTorch {:8.1f} us ({:.1f}x)\n", free1, torch1, torch1 / free1);
    fmt::print("  batch 64:  torch-free {:8.2f} us a sample, LibTorch {:8.2f} us a sample ({:.1f}x)\n", free64 / 64, torch64 / 64, torch64 / free64);
    fmt::print("  largest action difference {:.3g} ({:.3g} relative)\n", max_diff, max_relative);
    Controller probe({skill});
    (void)probe.step();
    const double dt = probe.control_dt();
    std::vector<std::pair<int, double>> crowd;
    for (const int n : args->crowd) {
      crowd.emplace_back(n, crowd_steps_per_second(skill, n, args->seconds));
      fmt::print("  crowd of {:4d}: {:9.0f} control steps/s on one core ({:.1f} x real time at {:.0f} Hz each)\n", n, crowd.back().second,
                 crowd.back().second * dt / n, 1.0 / dt);
    }
    // The cost of switching (seed 004 section 5.3): a request pending, its target scored every step.
    std::vector<std::pair<int, double>> switching;
    // (Skills with discriminators acting on a character: only a character is handed over.)
    if (!skill->discriminators().empty() && character_of(*make_skill_env(*skill))) {
      const std::shared_ptr<const Skill> candidate = Skill::load(args->model, skill->name() + "_candidate");
      for (const int n : args->crowd) {
        switching.emplace_back(n, crowd_steps_per_second(skill, n, args->seconds, candidate));
        fmt::print("  crowd of {:4d}, a switch pending: {:9.0f} control steps/s (its target's discriminators score every step)\n", n,
                   switching.back().second);
      }
    }
    if (args->json.empty()) return;
    std::string j = "{\n  \"model\": " + json_string(args->model.string()) + ",\n  \"inputs\": " + std::to_string(inputs.rows()) +
                    ",\n  \"policy_parameters\": " + std::to_string(skill->policy_parameters()) + ",\n  \"torch_free_us\": " + json_number(free1) +
                    ",\n  \"libtorch_us\": " + json_number(torch1) + ",\n  \"torch_free_batch64_us_per_sample\": " + json_number(free64 / 64) +
                    ",\n  \"libtorch_batch64_us_per_sample\": " + json_number(torch64 / 64) + ",\n  \"max_action_diff\": " + json_number(max_diff) +
                    ",\n  \"max_action_diff_relative\": " + json_number(max_relative) + ",\n  \"crowd\": [";
    for (std::size_t i = 0; i < crowd.size(); ++i)
      j += std::string(i ? ", " : "") + "{\"characters\": " + std::to_string(crowd[i].first) + ", \"steps_per_s\": " + json_number(crowd[i].second) + "}";
    j += "],\n  \"crowd_switching\": [";
    for (std::size_t i = 0; i < switching.size(); ++i)
      j += std::string(i ? ", " : "") + "{\"characters\": " + std::to_string(switching[i].first) + ", \"steps_per_s\": " +
           json_number(switching[i].second) + "}";
    j += "],\n  \"seconds_per_figure\": " + json_number(args->seconds) + "\n}\n";
    write_file_atomic(args->json, j);
    spdlog::info("wrote {}", args->json.string());
  });
}

}  // namespace mimic::app
