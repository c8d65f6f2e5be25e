#include "learn/trainer/train_bench.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <random>

#include "core/error.hpp"
#include "core/stopwatch.hpp"
#include "core/worker_pool.hpp"
#include "env/env_factory.hpp"
#include "learn/trainer/ranks.hpp"
#include "learn/trainer/trainer.hpp"

namespace mimic {

namespace {

// Control steps per second of `envs` environments stepped by `threads` workers with random actions.
double simulation_rate(const EnvFactory& factory, int envs, int threads, int steps_per_env) {
  std::vector<std::unique_ptr<Env>> pool_envs;
  std::vector<std::mt19937_64> rngs;
  for (int i = 0; i < envs; ++i) {
    pool_envs.push_back(factory());
    rngs.emplace_back(static_cast<std::uint64_t>(i) + 7);
    pool_envs.back()->reset(rngs.back());
  }
  WorkerPool pool(std::min(threads, envs));
  const Stopwatch clock;
  pool.run(envs, [&](int i) {
    Env& env = *pool_envs[static_cast<std::size_t>(i)];
    std::mt19937_64& rng = rngs[static_cast<std::size_t>(i)];
    std::normal_distribution<double> noise(0.0, 0.3);
    Eigen::VectorXd a(env.action_size());
    for (int t = 0; t < steps_per_env; ++t) {
      for (Eigen::Index j = 0; j < a.size(); ++j) a[j] = noise(rng);
      if (env.step(a).done()) env.reset(rng);
    }
  });
  return static_cast<double>(envs) * steps_per_env / clock.seconds();
}


double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

}  // namespace

TrainBenchResult median_of_rounds(const std::vector<TrainBenchResult>& of_rounds) {
  if (of_rounds.empty()) throw Error("bench train: no rounds to take the median of");
  const auto med = [&](double TrainBenchResult::*field) {
    std::vector<double> v;
    for (const auto& r : of_rounds) v.push_back(r.*field);
    return median(v);
  };
  TrainBenchResult m = of_rounds.front();
  for (double TrainBenchResult::*field : {&TrainBenchResult::sim_only_steps_per_s, &TrainBenchResult::train_samples_per_s, &TrainBenchResult::share_simulation,
                                          &TrainBenchResult::share_inference, &TrainBenchResult::share_learning, &TrainBenchResult::seconds,
                                          &TrainBenchResult::sums_per_iteration, &TrainBenchResult::bytes_per_iteration})
    m.*field = med(field);
  std::vector<double> ratios;
  for (const auto& r : of_rounds) ratios.push_back(r.train_samples_per_s / r.sim_only_steps_per_s);
  const auto [tmin, tmax] = std::minmax_element(of_rounds.begin(), of_rounds.end(), [](const auto& a, const auto& b) { return a.train_samples_per_s < b.train_samples_per_s; });
  m.train_min = tmin->train_samples_per_s;
  m.train_max = tmax->train_samples_per_s;
  m.of_sim_only = median(ratios);
  m.ratio_min = *std::min_element(ratios.begin(), ratios.end());
  m.ratio_max = *std::max_element(ratios.begin(), ratios.end());
  return m;
}

namespace {

// One setting's measurement: a fresh trainer, one warm-up iteration, then `opts.iterations` timed.
TrainBenchResult measure(const TrainBenchOptions& opts, int threads, bool overlap, const std::function<void(const std::string&)>& progress) {
  TrainConfig cfg = opts.config_text.empty() ? parse_train_config(train_benchmark_config(opts, threads), "bench train config")
                                             : parse_train_config(opts.config_text, opts.config_source);
  cfg.collect.threads = threads;
  cfg.collect.overlap = overlap;
  cfg.checkpoint_every = 1'000'000;  // (no checkpoint is written; none may interrupt the overlap)
  cfg.iterations = opts.iterations + 2;  // the last iteration collects nothing ahead: not timed
  cfg.tensorboard = false;
  TrainBenchResult r;
  r.threads = threads;
  r.overlap = overlap;
  r.ranks = ranks::size();
  Trainer trainer(cfg);
  // Every rank measures at once (as they train), and the rates add up.
  r.sim_only_steps_per_s = ranks::sum(simulation_rate(make_env_factory(cfg.env, YamlReader(cfg.source)), cfg.collect.envs, threads,
                                                      std::max(1, cfg.collect.samples / cfg.collect.envs)));
  if (progress) progress(fmt::format("{} thread(s){}: simulation only {:.0f} steps/s; training {} iterations...", threads, overlap ? ", learning overlapped" : "",
                                     r.sim_only_steps_per_s, opts.iterations + 1));
  trainer.iterate();  // warm-up: allocations, first normaliser statistics
  double sim = 0, inf = 0, learn = 0;
  long long samples = 0;
  const ranks::Traffic before = ranks::traffic();
  const Stopwatch clock;
  for (int i = 0; i < opts.iterations; ++i) {
    const IterationMetrics m = trainer.iterate();
    sim += m.get("time_simulation");
    inf += m.get("time_inference");
    learn += m.get("time_learning");
    samples = static_cast<long long>(m.get("samples"));
  }
  r.seconds = clock.seconds();
  const ranks::Traffic after = ranks::traffic();
  r.sums_per_iteration = static_cast<double>(after.sums - before.sums) / opts.iterations;
  r.bytes_per_iteration = static_cast<double>(after.bytes - before.bytes) / opts.iterations;
  const long long timed = samples - samples / (opts.iterations + 1);
  r.train_samples_per_s = static_cast<double>(timed) / r.seconds;
  r.of_sim_only = r.ratio_min = r.ratio_max = r.train_samples_per_s / r.sim_only_steps_per_s;
  r.train_min = r.train_max = r.train_samples_per_s;
  r.share_simulation = sim / r.seconds;
  r.share_inference = inf / r.seconds;
  r.share_learning = learn / r.seconds;
  if (progress) progress(fmt::format("{} thread(s): {:.0f} samples/s end to end", threads, r.train_samples_per_s));
  return r;
}

}  // namespace

std::string train_benchmark_config(const TrainBenchOptions& o, int threads) {
  return fmt::format(
      "# seed 004 Table 1 sizes on humanoid3d (move-forward task, episodes from the walk)\n"
      "seed: 1\n"
      "iterations: {}\n"
      "tensorboard: false\n"
      "env: {{name: imitation, init: mocap}}\n"
      "collect: {{envs: {}, threads: {}, samples: {}}}\n"
      "policy: {{hidden: [1024, 512], activation: relu, init: truncated_normal, init_std: 0.05,\n"
      "          output_init: truncated_normal, output_scale: 0.05, log_std: -1.0}}\n"
      "value: {{hidden: [1024, 512], activation: relu}}\n"
      "ppo: {{gamma: 0.95, lambda: 0.95, clip: 0.2, epochs: 5, value_epochs: 5, minibatch: 256, kl_stop: 0}}\n"
      "optimizer: {{kind: adam, policy_lr: 5.0e-6, value_lr: 1.0e-4}}\n",
      o.iterations + 1, o.envs, threads, o.samples);
}

std::vector<TrainBenchResult> run_train_benchmark(const TrainBenchOptions& opts, const std::function<void(const std::string&)>& progress) {
  std::vector<TrainBenchResult> out;
  std::vector<std::pair<int, bool>> settings;
  for (int threads : opts.threads) {
    settings.emplace_back(threads, false);
    if (opts.overlap) settings.emplace_back(threads, true);
  }
  if (opts.rounds < 1) throw Error("bench train: rounds must be >= 1");
  for (const auto& [threads, overlap] : settings)
    if (threads < 1) throw Error("bench train: thread counts must be >= 1");
  std::vector<std::vector<TrainBenchResult>> rounds(settings.size());
  for (int round = 0; round < opts.rounds; ++round)
    for (std::size_t k = 0; k < settings.size(); ++k) {
      if (progress && opts.rounds > 1 && k == 0) progress(fmt::format("round {} of {}", round + 1, opts.rounds));
      rounds[k].push_back(measure(opts, settings[k].first, settings[k].second, progress));
    }
  for (auto& of_setting : rounds) out.push_back(median_of_rounds(of_setting));
  return out;
}

std::string format_train_benchmark(const TrainBenchOptions& opts, const std::vector<TrainBenchResult>& results) {
  std::string s = opts.config_text.empty()
                      ? fmt::format("PPO on humanoid3d (34 DoF, 600 Hz physics / 30 Hz control), policy and value 1024-512, {} samples per "
                                    "iteration,\n5 epochs of minibatch 256, {} environments, {} timed iterations:\n\n",
                                    opts.samples, opts.envs, opts.iterations)
                      : fmt::format("{} ({} timed iterations):\n\n", opts.config_source, opts.iterations);
  if (opts.rounds > 1) s.insert(s.size() - 3, fmt::format(", each setting measured in {} rounds", opts.rounds));
  s += fmt::format(
      "| ranks | threads | overlap | sim only (steps/s) | end to end (samples/s) | of sim only | per thread | simulation | inference | "
      "learning | vs 1 thread |\n"
      "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
  double base = 0;
  for (const auto& r : results) {
    if (r.threads == 1 && r.ranks == 1 && !r.overlap) base = r.train_samples_per_s;
  }
  // (Over several ranks the time shares are rank 0's; overlapped, they add up to more than 100 %.)
  for (const auto& r : results)
    s += fmt::format("| {} | {} | {} | {:.0f} | {:.0f} | {:.2f} | {:.0f} | {:.0f}% | {:.0f}% | {:.0f}% | {} |\n", r.ranks, r.threads,
                     r.overlap ? "yes" : "no",
                     r.sim_only_steps_per_s, r.train_samples_per_s, r.of_sim_only,
                     r.train_samples_per_s / (r.threads * r.ranks), 100 * r.share_simulation, 100 * r.share_inference, 100 * r.share_learning,
                     base > 0 ? fmt::format("{:.2f}x", r.train_samples_per_s / base) : std::string("-"));
  if (opts.rounds > 1) {
    s += fmt::format("\n(Medians of {} rounds; \"of sim only\" is the median of each round's ratio.) Spread over the rounds:\n\n", opts.rounds);
    for (const auto& r : results)
      s += fmt::format("- {} rank(s), {} thread(s){}: end to end {:.0f}-{:.0f} samples/s, of sim only {:.2f}-{:.2f}\n", r.ranks, r.threads,
                       r.overlap ? ", overlapped" : "", r.train_min, r.train_max, r.ratio_min, r.ratio_max);
  }
  for (const auto& r : results)
    if (r.ranks > 1)
      s += fmt::format("\n{} ranks, {} thread(s){}: each rank put {:.0f} sums of {:.2f} MB in all into every iteration ({:.1f} kB a sum)\n", r.ranks,
                       r.threads, r.overlap ? ", overlapped" : "", r.sums_per_iteration, r.bytes_per_iteration / 1e6,
                       r.bytes_per_iteration / std::max(1.0, r.sums_per_iteration) / 1e3);
  return s;
}

}  // namespace mimic
