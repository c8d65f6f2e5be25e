#include "learn/trainer/trainer.hpp"

#include <ATen/Parallel.h>
#include <dlfcn.h>

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <future>
#include <numeric>

#include "core/error.hpp"
#include "core/file_io.hpp"
#include "core/stopwatch.hpp"
#include "env/context_env.hpp"
#include "learn/ppo/advantage.hpp"
#include "learn/rewards/adversarial_reward.hpp"
#include "learn/rewards/per_context_reward.hpp"
#include "learn/networks/runtime_export.hpp"
#include "learn/trainer/rank_sums.hpp"
#include "learn/trainer/trainer_impl.hpp"

namespace mimic {

namespace {

// One LibTorch intra-op thread and one OpenBLAS thread: parallelism comes from the environment
// workers and the concurrent value update (DESIGN.md: oversubscription was 5x slower).
void single_threaded_math() {
  at::set_num_threads(1);
  using SetThreads = void (*)(int);
  if (auto* f = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"))) f(1);
}

}  // namespace

Trainer::Impl::Impl(TrainConfig c, TrainOptions o) : cfg(std::move(c)), opts(std::move(o)) {
  single_threaded_math();
  torch::manual_seed(cfg.seed);
  const std::uint64_t seed = rank_seed(cfg.seed);
  noise_rng.seed(seed * 2 + 1);
  shuffle_rng.seed(seed * 2 + 2);
  if (ranks::many() && cfg.collect.mode == "episodes")
    throw Error(cfg.source + ": 'collect.mode: episodes' gives each rank a different number of samples; over several ranks (mpirun) collect by "
                "'collect.samples'");
  if (cfg.collect.overlap && cfg.init.kind == "adaptive")
    throw Error(cfg.source + ": 'collect.overlap' and 'init: {kind: adaptive}' cannot go together: the start distribution learns from the "
                "episodes the collection is still running");
  if (ranks::many() && cfg.init.kind == "adaptive")
    throw Error(cfg.source + ": 'init: {kind: adaptive}' learns its start distribution in one process; it does not run over several ranks (mpirun)");
  if (opts.env_factory) {
    factory = opts.env_factory;
  } else {
    if (!cfg.env.IsDefined()) throw Error(cfg.source + ": missing 'env': the environment to train in (e.g. env: {name: planar_walker})");
    factory = make_env_factory(cfg.env, YamlReader(cfg.source));
  }
  EnvFactory collect_factory = factory;
  if (cfg.init.kind == "adaptive") {
    const std::unique_ptr<Env> probe = factory();
    const auto* character = dynamic_cast<const CharacterEnv*>(probe.get());
    if (!character || !character->reference())
      throw Error(cfg.source + ": 'init: {kind: adaptive}' needs a character environment with a reference clip (e.g. env: {name: tracking})");
    adaptive_init = std::make_shared<AdaptiveInit>(std::make_shared<const Clip>(*character->reference()),
                                                   character->world().character().skeleton, cfg.init.adaptive);
    collect_factory = [inner = factory, dist = adaptive_init, gamma = cfg.ppo.gamma] {
      return std::unique_ptr<Env>(std::make_unique<AdaptiveInitEnv>(inner(), dist, gamma));
    };
  }
  collector = std::make_unique<Collector>(collect_factory, cfg.collect.envs, cfg.collect.threads, cfg.policy.net.history, seed);
  if (cfg.value.history != cfg.policy.net.history)
    throw Error(cfg.source + ": 'value.history' (" + std::to_string(cfg.value.history) + ") must equal 'policy.history' (" +
                std::to_string(cfg.policy.net.history) + "): both see the same input");
  {
    // An encoder's part of the observation, by name (learn/networks/networks.hpp).
    const std::vector<ObservationSlice> parts = collector->env(0).observation_layout();
    resolve_encoder(cfg.policy.net, parts, cfg.source + ": 'policy'");
    resolve_encoder(cfg.value, parts, cfg.source + ": 'value'");
  }
  {
    // Before anything large is allocated: both networks trained with Adam (4 bytes a value for
    // weights, gradients and two moments) and a rollout's buffers (per sample: normalised and raw
    // inputs, the next frame, the PPO batch's copy).
    std::string policy_shape, value_shape;
    const double networks = 16 * (feature_net_parameters(collector->input_size(), collector->action_size(), cfg.policy.net, policy_shape) +
                                  feature_net_parameters(collector->input_size(), 1, cfg.value, value_shape));
    const double per_sample = 16.0 * collector->input_size() + 8.0 * collector->frame_size() + 24.0 * collector->action_size() + 64;
    const double buffers = cfg.collect.mode == "episodes" ? 0.0 : per_sample * cfg.collect.samples;
    check_fits_memory(networks + buffers, cfg.source + ": the policy (" + policy_shape + "), the value network (" + value_shape +
                                              ") and 'collect.samples' " + std::to_string(cfg.collect.samples) + " together");
  }
  try {
    learner = std::make_unique<PpoLearner>(collector->input_size(), collector->action_size(), cfg);
  } catch (const Error& e) {
    throw Error(cfg.source + ": 'policy' and 'value': " + e.what());
  }
  obs_norm = RunningNormalizer(collector->input_size(), cfg.normalize.clip);
  return_norm = RunningNormalizer(1, 0.0);
  discounted_return.assign(static_cast<std::size_t>(cfg.collect.envs), 0.0);
  RewardSourceContext context;
  context.config_source = cfg.source;
  context.seed = seed;
  {
    const std::unique_ptr<Env> probe = factory();
    context.frame_size = probe->observation_size();
    context.action_size = probe->action_size();
    layout = probe->observation_layout();
    context.layout = layout;
  }
  for (const auto& rs : cfg.rewards) rewards.emplace_back(rs.weight, make_reward_source(rs, context));
  if (opts.step_hook) collector->set_step_hook([this](int n) { opts.step_hook(collecting_iteration, n); });
  if (opts.stop_requests && !ranks::many()) {
    // Collection and learning stop within a step or a minibatch of a request (Trainer::run).
    // Over several ranks a stop is agreed between iterations instead, where every rank is.
    auto requested = [stops = opts.stop_requests] { return stops() > 0; };
    collector->set_interrupt(requested);
    learner->set_interrupt(requested);
    for (auto& source : rewards) source.second->set_interrupt(requested);
  }
}

void Trainer::Impl::compute_rewards(Rollout& r) {
  r.reward.assign(static_cast<std::size_t>(r.size()), 0.0);
  for (auto& [w, source] : rewards) {
    const std::vector<double> part = source->rewards(r);
    if (part.size() != r.reward.size())
      throw Error("reward source '" + source->name() + "' gave " + std::to_string(part.size()) + " rewards for " + std::to_string(r.size()) + " samples");
    for (std::size_t i = 0; i < part.size(); ++i) {
      if (!std::isfinite(part[i]))
        throw TrainingDiverged("iteration " + std::to_string(iteration + 1) + ": reward source '" + source->name() + "' gave a non-finite reward (" +
                               std::to_string(part[i]) + " for sample " + std::to_string(i) + "); " + divergence::kStopping);
      r.reward[i] += w * part[i];
    }
  }
  if (!cfg.normalize.rewards) return;
  // Seed 002: divide rewards by the running std of the discounted return, per environment in time order.
  std::vector<double> returns;
  for (int e = 0; e < r.envs; ++e)
    for (int i : r.env_steps[static_cast<std::size_t>(e)]) {
      double& g = discounted_return[static_cast<std::size_t>(e)];
      g = cfg.ppo.gamma * g + r.reward[static_cast<std::size_t>(i)];
      returns.push_back(g);
      if (r.ended[static_cast<std::size_t>(i)]) g = 0.0;
    }
  update_over_ranks(return_norm, Eigen::MatrixXd(Eigen::Map<const Eigen::MatrixXd>(returns.data(), static_cast<Eigen::Index>(returns.size()), 1)));
  const double scale = 1.0 / std::sqrt(return_norm.variance()[0] + 1e-8);
  for (double& x : r.reward) x *= scale;
}

PpoBatch Trainer::Impl::make_batch(const Rollout& r) const {
  std::vector<AdvantageStep> steps;
  std::vector<double> advantage(static_cast<std::size_t>(r.size())), target(advantage.size());
  for (int e = 0; e < r.envs; ++e) {
    const auto& idx = r.env_steps[static_cast<std::size_t>(e)];
    steps.clear();
    for (int i : idx) {
      const auto u = static_cast<std::size_t>(i);
      steps.push_back({r.reward[u], r.value[u], r.next_value[u], r.ended[u] != 0, r.failed[u] != 0});
    }
    const Advantages a = compute_advantages(steps, cfg.ppo.gamma, cfg.ppo.lambda);
    for (std::size_t j = 0; j < idx.size(); ++j) {
      advantage[static_cast<std::size_t>(idx[j])] = a.advantage[j];
      target[static_cast<std::size_t>(idx[j])] = a.target[j];
    }
  }
  const std::int64_t n = r.size(), in = r.input_size, na = r.action_size;
  auto floats = [](const std::vector<float>& v, std::vector<std::int64_t> shape) {
    return torch::from_blob(const_cast<float*>(v.data()), shape, torch::kFloat32).clone();
  };
  auto doubles = [](const std::vector<double>& v) {
    return torch::from_blob(const_cast<double*>(v.data()), {static_cast<std::int64_t>(v.size())}, torch::kFloat64).to(torch::kFloat32);
  };
  PpoBatch b;
  b.input = floats(r.input, {n, in});
  b.action = floats(r.action, {n, na});
  b.old_mean = floats(r.mean, {n, na});
  b.old_log_std = floats(r.log_std, {n, na});
  b.old_value = floats(r.value, {n});
  b.advantage = doubles(advantage);
  b.target = doubles(target);
  return b;
}

Trainer::Impl::Collected Trainer::Impl::collect(int for_iteration, GaussianPolicy& policy, ValueNet& value, const RunningNormalizer& norm) {
  collecting_iteration = for_iteration;
  Collected c;
  c.rollout = cfg.collect.mode == "episodes"
                  ? collector->collect_episodes(cfg.collect.episodes, policy, value, norm, noise_rng)
                  : collector->collect_steps(std::max(1, cfg.collect.samples / cfg.collect.envs), policy, value, norm, noise_rng);
  c.episodes = collector->take_episode_stats();
  c.times = collector->take_times();
  return c;
}

void Trainer::Impl::refresh_values(Rollout& r) {
  torch::NoGradGuard no_grad;
  const torch::Tensor v = learner->value()->forward(torch::from_blob(r.input.data(), {r.size(), r.input_size}, torch::kFloat32)).contiguous();
  r.value.assign(v.data_ptr<float>(), v.data_ptr<float>() + r.size());
  // The state after a step is the next sample of the same environment, but after an episode's end
  // and after the horizon's last step, whose bootstrap values stay the acting copy's (their
  // inputs are not kept).
  for (const auto& idx : r.env_steps)
    for (std::size_t j = 0; j + 1 < idx.size(); ++j)
      if (!r.ended[static_cast<std::size_t>(idx[j])])
        r.next_value[static_cast<std::size_t>(idx[j])] = r.value[static_cast<std::size_t>(idx[j + 1])];
}

IterationMetrics Trainer::Impl::iterate() {
  const Stopwatch iteration_time;
  learner->set_progress(static_cast<double>(iteration) / cfg.iterations);
  Collected collected = prefetched ? std::move(*prefetched) : collect(iteration + 1, learner->policy(), learner->value(), obs_norm);
  prefetched.reset();
  Rollout& r = collected.rollout;
  compute_rewards(r);
  // collect.overlap: the next iteration's rollout is collected with this policy while it learns;
  // not before a checkpoint or past the end, so that a resumed run goes on as the saving one did.
  std::future<Collected> next;
  if (cfg.collect.overlap && (iteration + 1) % cfg.checkpoint_every != 0 && iteration + 1 < cfg.iterations) {
    if (!acting) acting = std::make_unique<ActingCopy>(collector->input_size(), collector->action_size(), cfg);
    acting->take(learner->policy(), learner->value(), obs_norm);
    next = std::async(std::launch::async, [this, ahead = iteration + 2] {
      Collected c = collect(ahead, acting->policy(), acting->value(), acting->norm());
      c.stale = true;
      return c;
    });
  }
  const Stopwatch learning;
  if (collected.stale) refresh_values(r);
  PpoBatch batch = make_batch(r);
  if (collected.stale) {
    // Collected by the previous iteration's policy: the update is decoupled PPO around this one.
    torch::NoGradGuard no_grad;
    const auto [mean, log_std] = learner->policy()->forward(batch.input);
    batch.prox_mean = mean.clone();
    batch.prox_log_std = log_std.clone();  // (the forward's is a view of the parameter the update changes)
  }
  const PpoStats s = learner->update(batch, shuffle_rng, cfg.collect.threads > 1, iteration + 1);
  std::vector<std::pair<std::string, double>> source_metrics;
  for (auto& [w, source] : rewards) {
    try {
      for (auto& m : source->update(r)) source_metrics.emplace_back(source->name() + "_" + m.first, m.second);
    } catch (const TrainingDiverged& e) {
      throw TrainingDiverged("iteration " + std::to_string(iteration + 1) + ", reward source '" + source->name() + "', " + e.what());
    }
  }
  if (cfg.normalize.observations)
    update_over_ranks(obs_norm, Eigen::MatrixXd(Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(r.raw_input.data(), r.size(), r.input_size)));
  const double learn_seconds = learning.seconds();
  if (next.valid()) prefetched = next.get();

  ++iteration;
  // Samples, episodes and rewards of every rank (the run's, not one process's).
  const EpisodeStats& ep = collected.episodes;
  std::array<double, 6> totals{static_cast<double>(r.size()), static_cast<double>(ep.returns.size()),
                               std::accumulate(ep.returns.begin(), ep.returns.end(), 0.0),
                               static_cast<double>(std::accumulate(ep.lengths.begin(), ep.lengths.end(), 0LL)), static_cast<double>(ep.failures),
                               std::accumulate(r.reward.begin(), r.reward.end(), 0.0)};
  ranks::sum(totals);
  const auto [rollout_samples, episodes, return_sum, length_sum, failures, reward_sum] = totals;
  samples += static_cast<long long>(rollout_samples);
  const double seconds = iteration_time.seconds();
  wall_seconds += seconds;
  const CollectTimes& times = collected.times;

  IterationMetrics m;
  m.iteration = iteration;
  m.set("samples", static_cast<double>(samples));
  m.set("wall_s", wall_seconds);
  m.set("samples_per_s", rollout_samples / seconds);
  const double no_value = std::nan("");
  m.set("return", episodes > 0 ? return_sum / episodes : no_value);
  m.set("episode_length", episodes > 0 ? length_sum / episodes : no_value);
  m.set("episodes", episodes);
  m.set("failure_rate", episodes > 0 ? failures / episodes : no_value);
  m.set("reward", rollout_samples > 0 ? reward_sum / rollout_samples : no_value);
  m.set("policy_loss", s.policy_loss);
  m.set("value_loss", s.value_loss);
  m.set("kl", s.kl);
  m.set("entropy", s.entropy);
  m.set("clip_fraction", s.clip_fraction);
  m.set("explained_variance", s.explained_variance);
  m.set("kl_beta", s.beta);
  m.set("policy_epochs", s.policy_epochs);
  m.set("policy_grad_norm", s.policy_grad_norm);
  m.set("value_grad_norm", s.value_grad_norm);
  m.set("policy_lr", s.policy_lr);
  m.set("value_lr", s.value_lr);
  m.set("time_simulation", times.simulation);
  m.set("time_inference", times.inference);
  m.set("time_learning", learn_seconds);
  for (const auto& [name, sum] : r.term_sums) m.set("term_" + name, sum / r.size());
  for (const auto& [name, sum] : r.info_sums) m.set("info_" + name, sum / r.size());
  for (const auto& [name, v] : source_metrics) m.set(name, v);
  if (adaptive_init) update_adaptive_init(m);
  return m;
}

void Trainer::Impl::update_adaptive_init(IterationMetrics& m) {
  for (int e = 0; e < collector->envs(); ++e)
    for (auto& o : dynamic_cast<AdaptiveInitEnv&>(collector->env(e)).take_outcomes()) init_pending.push_back(std::move(o));
  if (static_cast<int>(init_pending.size()) >= cfg.init.adaptive.batch_episodes) {
    adaptive_init->update(init_pending);
    init_pending.clear();
    ++init_updates;
  }
  // How far the distribution has moved: mean |mean| and mean sigma, both over the initial sigma.
  const AdaptiveInit& d = *adaptive_init;
  const Eigen::RowVectorXd sigma0 = d.initial_std().transpose();
  m.set("init_updates", init_updates);
  m.set("init_mean_shift", (d.means().array().abs().rowwise() / sigma0.array()).mean());
  m.set("init_std_ratio", (d.log_std().array().exp().rowwise() / sigma0.array()).mean());
}

namespace {

// A run or model directory stands for its checkpoint.pt; a file for itself.
std::filesystem::path checkpoint_of(const std::filesystem::path& p) {
  return std::filesystem::is_directory(p) ? p / "checkpoint.pt" : p;
}

// A resumed run must go on with the config it was started with: its networks, normalisers and
// discriminators were built from it, and its config.yaml has to keep describing the checkpoint.
// Another one (another file, an edit) would either fail deep in the checkpoint or, worse,
// silently change learning rates or rewards half-way through.
void require_same_config(const TrainConfig& cfg, const std::filesystem::path& saved_path) {
  const std::string difference = config_difference(read_text_file(saved_path), saved_path.string(), cfg.text, cfg.source);
  if (difference.empty()) return;
  throw Error(cfg.source + ": differs from " + saved_path.string() + ", the config the run was started with (" + difference +
              "); resume with `mimic train --resume -o " + saved_path.parent_path().string() + "` (--iterations and --threads may change)");
}

// `f()`, whose Error about RUN/checkpoint.pt gains what RUN/checkpoint.prev.pt offers instead.
template <class F>
bool with_previous_hint(const std::filesystem::path& dir, F&& f) {
  try {
    return f();
  } catch (const TrainingDiverged&) {
    throw;
  } catch (const Error& e) {
    const std::filesystem::path previous = dir / "checkpoint.prev.pt";
    if (!std::filesystem::exists(previous)) throw;
    std::string offer;
    try {
      offer = "; the previous checkpoint " + previous.string() + " is intact (iteration " + std::to_string(checkpoint_iteration(previous)) +
              "): move it over checkpoint.pt to resume from there";
    } catch (const Error& p) {
      offer = "; the previous checkpoint is unusable too (" + std::string(p.what()) + ")";
    }
    throw Error(e.what() + offer);
  }
}

}  // namespace

Trainer::Trainer(TrainConfig cfg, TrainOptions opts) {
  const std::filesystem::path dir = opts.run_dir;
  const bool resume = opts.resume;
  if (!dir.empty() && !resume && std::filesystem::exists(dir / "checkpoint.pt"))
    throw Error(dir.string() + " already holds a run (checkpoint.pt): pass --resume to continue it, or choose another output directory");
  if (resume && dir.empty()) throw Error("resume needs a run directory");
  if (resume && !opts.init_from.empty()) throw Error("a resumed run goes on from its own checkpoint; --init-from is for a new run");
  if (resume && !opts.init_discriminators_from.empty())
    throw Error("a resumed run goes on from its own checkpoint; --init-discriminators-from is for a new run");
  if (resume && !std::filesystem::exists(dir / "checkpoint.pt"))
    throw Error((dir / "checkpoint.pt").string() + ": no checkpoint to resume from");
  if (resume && std::filesystem::exists(dir / "config.yaml")) require_same_config(cfg, dir / "config.yaml");
  // Over several ranks only rank 0 writes the run's files; the others read its checkpoint to resume.
  const bool writer = ranks::rank() == 0;
  // What an interrupted atomic write left (a kill in the middle of a checkpoint): never read.
  if (!dir.empty() && writer) remove_stale_temporaries(dir), remove_stale_temporaries(dir / "snapshots");
  // Before the reward sources are built: an exported model's expert files may not travel with it.
  if (resume && with_previous_hint(dir, [&] { return is_exported_checkpoint(dir / "checkpoint.pt"); }))
    throw Error((dir / "checkpoint.pt").string() +
                ": an exported model (mimic export: no optimiser moments, no discriminator replay) acts but is not resumed; resume the run it was exported from");
  const std::string text = cfg.text, cfg_source = cfg.source;
  const std::filesystem::path init_from = opts.init_from;
  const std::vector<std::filesystem::path> discriminators_from = opts.init_discriminators_from;
  impl_ = std::make_unique<Impl>(std::move(cfg), std::move(opts));
  if (!init_from.empty()) impl_->sources_from_init = read_weights(*impl_, checkpoint_of(init_from));
  if (!discriminators_from.empty()) {
    std::vector<std::filesystem::path> checkpoints;
    for (const auto& p : discriminators_from) checkpoints.push_back(checkpoint_of(p));
    impl_->context_discriminators_from_init = read_context_discriminators(*impl_, checkpoints);
  }
  if (dir.empty()) return;
  if (resume) {
    with_previous_hint(dir, [&] {
      load_checkpoint(dir / "checkpoint.pt");
      return true;
    });
    // The count this resume goes on to becomes the run's own, so a later plain --resume keeps it.
    if (writer && std::filesystem::exists(dir / "config.yaml")) {
      const std::string saved = read_text_file(dir / "config.yaml");
      const std::string updated = with_iterations(saved, (dir / "config.yaml").string(), impl_->cfg.iterations);
      if (updated != saved) write_file_atomic(dir / "config.yaml", updated);
    }
  } else if (writer) {
    std::filesystem::create_directories(dir);
    // The run's own record of where its weights came from (a comment: resume ignores it).
    std::string origin = init_from.empty() ? "" : "# started from the weights of " + init_from.string() + " (mimic train --init-from)\n";
    if (!discriminators_from.empty()) {
      origin += "# discriminators per context started from";
      for (const auto& p : discriminators_from) origin += " " + p.string();
      origin += " (mimic train --init-discriminators-from)\n";
    }
    // With the count this run goes to (an --iterations override), so a plain --resume keeps it.
    write_file_atomic(dir / "config.yaml", with_iterations(origin + text, cfg_source, impl_->cfg.iterations));
  }
  if (writer) impl_->log = std::make_unique<RunLog>(dir, impl_->cfg.tensorboard, resume ? impl_->iteration : -1);
}

Trainer::~Trainer() = default;

IterationMetrics Trainer::iterate() {
  IterationMetrics m = impl_->iterate();
  // The iteration is complete and healthy (iterate() throws on divergence before this point).
  if (impl_->log) impl_->log->write(m);
  if (impl_->opts.on_iteration) impl_->opts.on_iteration(m);
  const std::filesystem::path& dir = impl_->opts.run_dir;
  if (impl_->cfg.snapshot_every > 0 && m.iteration % impl_->cfg.snapshot_every == 0 && !dir.empty() && ranks::rank() == 0) {
    std::filesystem::create_directories(dir / "snapshots");
    write_policy_snapshot(*impl_, snapshot_path(dir, m.iteration));
  }
  if (m.iteration % impl_->cfg.checkpoint_every == 0) {
    if (!dir.empty()) impl_->save_run_checkpoint(serialize_checkpoint(*impl_));
    // Episodes restart at every checkpoint, so that a resumed run matches the uninterrupted one.
    impl_->collector->reset_all();
    std::fill(impl_->discounted_return.begin(), impl_->discounted_return.end(), 0.0);
  } else if (!dir.empty() && impl_->opts.stop_requests) {
    // Held in memory, so that a stop in the next iteration still saves this one.
    impl_->unsaved_checkpoint = serialize_checkpoint(*impl_);
  }
  return m;
}

void Trainer::Impl::save_run_checkpoint(const std::string& bytes) {
  if (ranks::rank() == 0) write_file_atomic_keeping(opts.run_dir / "checkpoint.pt", opts.run_dir / "checkpoint.prev.pt", bytes);
  unsaved_checkpoint.clear();
}

RunEnd Trainer::run() {
  const bool files = !impl_->opts.run_dir.empty();
  // A fresh run stopped in its first iteration still leaves a checkpoint (of iteration 0).
  if (files && impl_->opts.stop_requests && ranks::any(!std::filesystem::exists(impl_->opts.run_dir / "checkpoint.pt")))
    impl_->unsaved_checkpoint = serialize_checkpoint(*impl_);
  RunEnd end;
  // Over several ranks every rank must stop after the same iteration: a stop is agreed between them.
  const auto stop_requested = [&] { return ranks::any(impl_->opts.stop_requests && impl_->opts.stop_requests() > 0); };
  while (impl_->iteration < impl_->cfg.iterations && !stop_requested()) {
    try {
      iterate();
    } catch (const Interrupted& e) {
      end.interrupted = e.what();  // the networks may be part-updated: only the last complete iteration is saved
      break;
    }
  }
  end.stopped = impl_->iteration < impl_->cfg.iterations;
  end.iteration = impl_->iteration;
  if (!files) return end;
  if (!impl_->unsaved_checkpoint.empty()) {
    impl_->save_run_checkpoint(impl_->unsaved_checkpoint);
  } else if (!end.stopped && impl_->iteration % impl_->cfg.checkpoint_every != 0) {
    impl_->save_run_checkpoint(serialize_checkpoint(*impl_));  // a run not stopped ends with its last iteration saved
  } else if (ranks::any(!std::filesystem::exists(impl_->opts.run_dir / "checkpoint.pt"))) {
    impl_->save_run_checkpoint(serialize_checkpoint(*impl_));
  }
  return end;
}

long long Trainer::policy_parameters() const {
  long long n = 0;
  for (const auto& p : impl_->learner->policy()->parameters()) n += p.numel();
  return n;
}

int Trainer::iteration() const { return impl_->iteration; }
int Trainer::saved_ranks() const { return impl_->saved_ranks; }
int Trainer::reward_sources_initialised() const { return impl_->sources_from_init; }
int Trainer::context_discriminators_initialised() const { return impl_->context_discriminators_from_init; }
int Trainer::contexts_added_by_init() const { return impl_->contexts_added_by_init; }
const std::vector<std::string>& Trainer::parts_added_by_init() const { return impl_->parts_added_by_init; }
long long Trainer::samples() const { return impl_->samples; }
int Trainer::input_size() const { return impl_->collector->input_size(); }
int Trainer::action_size() const { return impl_->collector->action_size(); }
const TrainConfig& Trainer::config() const { return impl_->cfg; }
void Trainer::save_checkpoint(const std::filesystem::path& path) const { write_file_atomic(path, serialize_checkpoint(*impl_)); }
void Trainer::load_checkpoint(const std::filesystem::path& path) { read_checkpoint(*impl_, path); }

void Trainer::export_model(const std::filesystem::path& path) {
  impl_->learner->policy_optimizer().state().clear();
  impl_->learner->value_optimizer().state().clear();
  for (auto& source : impl_->rewards) source.second->drop_training_state();
  impl_->acting_only = true;
  write_file_atomic(path, serialize_checkpoint(*impl_));
  write_runtime_networks(path.parent_path() / kRuntimeFileName);
}

void Trainer::write_runtime_networks(const std::filesystem::path& path) const { write_runtime_file(*impl_, path); }
std::string Trainer::runtime_networks() const { return encode_arrays(runtime_arrays(*impl_)); }

std::filesystem::path Trainer::snapshot_path(const std::filesystem::path& run, int iteration) {
  return run / "snapshots" / fmt::format("{:06d}.pt", iteration);
}

std::vector<std::pair<int, std::filesystem::path>> Trainer::policy_snapshots(const std::filesystem::path& run) {
  std::vector<std::pair<int, std::filesystem::path>> out;
  const std::filesystem::path dir = run / "snapshots";
  if (!std::filesystem::is_directory(dir)) return out;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::string stem = entry.path().stem().string();
    if (entry.path().extension() != ".pt" || stem.empty() || stem.size() > 9 ||
        !std::all_of(stem.begin(), stem.end(), [](char c) { return c >= '0' && c <= '9'; }))
      continue;  // not one of ours (a copy, an editor's file)
    out.emplace_back(std::stoi(stem), entry.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

double Trainer::average_policy_with(const std::vector<std::filesystem::path>& checkpoints) {
  std::vector<std::filesystem::path> files;
  for (const auto& p : checkpoints) files.push_back(checkpoint_of(p));
  return average_policy(*impl_, files);
}

void Trainer::take_policy_from(const std::filesystem::path& checkpoint) {
  read_policy(*impl_, checkpoint_of(checkpoint));
}

std::unique_ptr<Trainer> Trainer::from_run(const std::filesystem::path& run, bool reward_sources, const std::vector<std::string>& settings) {
  const std::filesystem::path config = run / "config.yaml", checkpoint = run / "checkpoint.pt";
  if (!std::filesystem::exists(config) || !std::filesystem::exists(checkpoint))
    throw Error(run.string() + ": not a training run (needs config.yaml and checkpoint.pt)");
  // Without reward sources their saved state is skipped: the env source loads nothing.
  std::vector<std::string> overrides = settings;
  if (!reward_sources) overrides.push_back("rewards=[{source: env}]");
  const std::string raw = read_text_file(config);
  const std::string text = overrides.empty() ? raw : override_config(raw, config.string(), overrides);
  auto trainer = std::make_unique<Trainer>(parse_train_config(text, config.string()));
  trainer->load_checkpoint(checkpoint);
  return trainer;
}

const std::vector<ObservationSlice>& Trainer::observation_layout() const { return impl_->layout; }

Rollout Trainer::Impl::side_episodes(int episodes, std::uint64_t seed, std::mt19937_64& rng, bool deterministic, EpisodeStats& stats) {
  Collector side(factory, std::min(episodes, cfg.collect.envs), cfg.collect.threads, cfg.policy.net.history, seed);
  Rollout r = side.collect_episodes(episodes, learner->policy(), learner->value(), obs_norm, rng, deterministic);
  stats = side.take_episode_stats();
  return r;
}

Demonstrations Trainer::Impl::record(int episodes, bool deterministic, std::uint64_t seed, EpisodeStats& stats) {
  std::mt19937_64 rng(seed);  // action noise, then the sub-sampling offsets
  const Rollout r = side_episodes(episodes, seed, rng, deterministic, stats);
  return demonstrations_of(r, layout, 1, rng);
}

}  // namespace mimic
