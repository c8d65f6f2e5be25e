#include "learn/ppo/collector.hpp"

#include <cmath>
#include <sstream>

#include "core/error.hpp"
#include "core/stopwatch.hpp"

namespace mimic {

namespace {

// Adds each named value to its running sum, a new name making a new sum (in first-seen order).
void add_to_sums(std::vector<std::pair<std::string, double>>& sums, const std::vector<std::pair<std::string, double>>& values) {
  for (const auto& [name, v] : values) {
    auto it = std::find_if(sums.begin(), sums.end(), [&](const auto& p) { return p.first == name; });
    if (it == sums.end()) sums.emplace_back(name, v);
    else it->second += v;
  }
}

}  // namespace

// One environment's running state between steps.
struct Collector::Slot {
  std::mt19937_64 rng;
  FrameHistory frames;
  double episode_return = 0.0;
  int episode_length = 0;
  bool idle = false;  // episodes mode: this slot has finished its share
  // Results of the latest step, written by the worker.
  StepResult result;
  Eigen::VectorXd action;
};

Collector::Collector(const EnvFactory& factory, int envs, int threads, int history, std::uint64_t seed)
    : pool_(std::min(threads, envs)), history_(history) {
  if (envs < 1) throw Error("collector: at least one environment is needed");
  if (history < 1) throw Error("collector: history must be >= 1");
  std::seed_seq seq{seed, std::uint64_t{0x6d696d6963}};  // "mimic"
  std::vector<std::uint64_t> seeds(static_cast<std::size_t>(envs));
  seq.generate(seeds.begin(), seeds.end());
  for (int i = 0; i < envs; ++i) {
    envs_.push_back(factory());
    auto slot = std::make_unique<Slot>();
    slot->rng.seed(seeds[static_cast<std::size_t>(i)]);
    slots_.push_back(std::move(slot));
  }
  frame_size_ = envs_[0]->observation_size();
  action_size_ = envs_[0]->action_size();
  reset_all();
}

Collector::~Collector() = default;

void Collector::reset_slot(int i) {
  Slot& s = *slots_[static_cast<std::size_t>(i)];
  const Eigen::VectorXd obs = envs_[static_cast<std::size_t>(i)]->reset(s.rng);
  if (obs.size() != frame_size_ || !obs.allFinite())
    throw Error("environment " + std::to_string(i) + ": reset gave a non-finite or wrongly sized observation");
  s.frames = FrameHistory(history_);
  s.frames.reset(obs);
  s.episode_return = 0.0;
  s.episode_length = 0;
}

void Collector::reset_all() {
  pool_.run(envs(), [this](int i) { reset_slot(i); });
  for (auto& s : slots_) s->idle = false;
}

EpisodeStats Collector::take_episode_stats() { return std::exchange(stats_, {}); }
CollectTimes Collector::take_times() { return std::exchange(times_, {}); }

std::vector<std::string> Collector::rng_states() const {
  std::vector<std::string> out;
  for (const auto& s : slots_) {
    std::ostringstream os;
    os << s->rng;
    out.push_back(os.str());
  }
  return out;
}

void Collector::set_rng_states(const std::vector<std::string>& states) {
  if (states.size() != slots_.size())
    throw Error("collector: " + std::to_string(states.size()) + " saved generator states for " + std::to_string(slots_.size()) + " environments");
  for (std::size_t i = 0; i < states.size(); ++i) {
    std::istringstream is(states[i]);
    is >> slots_[i]->rng;
    if (!is) throw Error("collector: saved generator state " + std::to_string(i) + " is unreadable");
  }
}

Rollout Collector::collect_steps(int steps, GaussianPolicy& policy, ValueNet& value, const RunningNormalizer& norm,
                                 std::mt19937_64& noise_rng, bool deterministic) {
  if (steps < 1) throw Error("collector: steps must be >= 1");
  return collect(steps, 0, policy, value, norm, noise_rng, deterministic);
}

Rollout Collector::collect_episodes(int episodes, GaussianPolicy& policy, ValueNet& value, const RunningNormalizer& norm,
                                    std::mt19937_64& noise_rng, bool deterministic) {
  if (episodes < 1) throw Error("collector: episodes must be >= 1");
  reset_all();
  return collect(0, episodes, policy, value, norm, noise_rng, deterministic);
}

Rollout Collector::collect(int steps, int episodes, GaussianPolicy& policy, ValueNet& value, const RunningNormalizer& norm,
                           std::mt19937_64& noise_rng, bool deterministic) {
  torch::NoGradGuard no_grad;
  const int n_env = envs(), in = input_size(), na = action_size_;
  const bool by_episodes = episodes > 0;
  Rollout r;
  r.input_size = in, r.frame_size = frame_size_, r.action_size = na, r.envs = n_env;
  r.env_steps.resize(static_cast<std::size_t>(n_env));
  int started = 0;  // episodes mode: episodes begun (each slot starts one now)
  if (by_episodes) {
    for (int e = 0; e < n_env; ++e) slots_[static_cast<std::size_t>(e)]->idle = e >= episodes;
    started = std::min(episodes, n_env);
  }
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::vector<int> active;
  // Inputs whose value bootstraps an ended-by-truncation step: (sample, raw input).
  std::vector<std::pair<int, Eigen::VectorXd>> bootstrap;

  for (int t = 0; steps == 0 || t < steps; ++t) {
    active.clear();
    for (int e = 0; e < n_env; ++e)
      if (!slots_[static_cast<std::size_t>(e)]->idle) active.push_back(e);
    if (active.empty()) break;
    const int b = static_cast<int>(active.size());

    // Batched inference over the active environments.
    Stopwatch inference;
    Eigen::MatrixXd raw(b, in);
    for (int k = 0; k < b; ++k) {
      raw.row(k) = slots_[static_cast<std::size_t>(active[static_cast<std::size_t>(k)])]->frames.stacked().transpose();
    }
    const Eigen::MatrixXf x = norm.normalize(raw).cast<float>();
    // Eigen is column-major: transpose into a row-major buffer for torch.
    Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> xr = x;
    const torch::Tensor input = torch::from_blob(xr.data(), {b, in}, torch::kFloat32);
    auto [mean_t, log_std_t] = policy->forward(input);
    mean_t = mean_t.contiguous();
    log_std_t = log_std_t.contiguous();
    const float* mean_p = mean_t.data_ptr<float>();
    const float* log_std_p = log_std_t.data_ptr<float>();

    const std::size_t base = r.env_reward.size();
    for (int k = 0; k < b; ++k) {
      const int e = active[static_cast<std::size_t>(k)];
      Slot& s = *slots_[static_cast<std::size_t>(e)];
      s.action.resize(na);
      // The learner recomputes log-probabilities from the stored mean and log sigma.
      for (int j = 0; j < na; ++j) {
        const double mu = mean_p[k * na + j], ls = log_std_p[k * na + j];
        const double z = deterministic ? 0.0 : gauss(noise_rng);
        const float a = static_cast<float>(mu + std::exp(ls) * z);
        s.action[j] = a;
        r.action.push_back(a);
        r.mean.push_back(mean_p[k * na + j]);
        r.log_std.push_back(log_std_p[k * na + j]);
      }
      r.value.push_back(0.0f);  // all values at once after the collection (below)
      for (int c = 0; c < in; ++c) r.raw_input.push_back(raw(k, c));
      r.input.insert(r.input.end(), xr.row(k).data(), xr.row(k).data() + in);
      r.env_steps[static_cast<std::size_t>(e)].push_back(static_cast<int>(base) + k);
      r.env_reward.push_back(0.0);
      r.ended.push_back(0);
      r.failed.push_back(0);
      r.next_value.push_back(0.0);
    }
    times_.inference += inference.seconds();

    // Step every active environment in parallel; each touches only its own slot.
    Stopwatch stepping;
    pool_.run(b, [&](int k) {
      const int e = active[static_cast<std::size_t>(k)];
      Slot& s = *slots_[static_cast<std::size_t>(e)];
      s.result = envs_[static_cast<std::size_t>(e)]->step(s.action.cast<double>());
    });
    times_.simulation += stepping.seconds();

    // Record results in environment order, then start new episodes where one ended.
    std::vector<int> to_reset;
    for (int k = 0; k < b; ++k) {
      const int e = active[static_cast<std::size_t>(k)];
      Slot& s = *slots_[static_cast<std::size_t>(e)];
      const StepResult& res = s.result;
      const std::size_t i = base + static_cast<std::size_t>(k);
      if (res.observation.size() != frame_size_ || !res.observation.allFinite())
        throw Error("environment " + std::to_string(e) + ": step " + std::to_string(s.episode_length + 1) +
                    " of its episode gave a non-finite or wrongly sized observation");
      const double rew = res.reward();
      if (!std::isfinite(rew)) throw Error("environment " + std::to_string(e) + ": non-finite reward at step " + std::to_string(s.episode_length + 1));
      r.env_reward[i] = rew;
      add_to_sums(r.term_sums, res.reward_terms);
      add_to_sums(r.info_sums, res.info);
      r.next_obs.insert(r.next_obs.end(), res.observation.data(), res.observation.data() + frame_size_);
      s.frames.push(res.observation);
      s.episode_return += rew;
      ++s.episode_length;
      if (res.done()) {
        r.ended[i] = 1;
        r.failed[i] = is_failure(res.termination) ? 1 : 0;
        stats_.returns.push_back(s.episode_return);
        stats_.lengths.push_back(s.episode_length);
        if (r.failed[i]) ++stats_.failures;
        if (!r.failed[i]) bootstrap.emplace_back(static_cast<int>(i), s.frames.stacked());
        if (by_episodes && started >= episodes) s.idle = true;
        else {
          if (by_episodes) ++started;
          to_reset.push_back(e);
        }
      }
    }
    if (!to_reset.empty()) {
      Stopwatch resetting;
      pool_.run(static_cast<int>(to_reset.size()), [&](int k) { reset_slot(to_reset[static_cast<std::size_t>(k)]); });
      times_.simulation += resetting.seconds();
    }
    if (step_hook_) step_hook_(r.size());
    if (interrupted_ && interrupted_()) throw Interrupted("stopped during collection, " + std::to_string(r.size()) + " samples in");
  }

  // Every sample's value in one batched pass (the network does not change during a collection):
  // one large product instead of a small one per step, which cost as much again as the policy's.
  Stopwatch bootstrapping;
  if (r.size() > 0) {
    const torch::Tensor v = value->forward(torch::from_blob(r.input.data(), {r.size(), in}, torch::kFloat32)).contiguous();
    r.value.assign(v.data_ptr<float>(), v.data_ptr<float>() + r.size());
  }
  // Values that bootstrap: the state after each step is the next sample of the same environment,
  // except after an ended episode (its last observation) and after the last step (the current one).
  for (int e = 0; e < n_env; ++e) {
    const auto& idx = r.env_steps[static_cast<std::size_t>(e)];
    for (std::size_t j = 0; j + 1 < idx.size(); ++j)
      if (!r.ended[static_cast<std::size_t>(idx[j])]) r.next_value[static_cast<std::size_t>(idx[j])] = r.value[static_cast<std::size_t>(idx[j + 1])];
    if (!idx.empty() && !r.ended[static_cast<std::size_t>(idx.back())])
      bootstrap.emplace_back(idx.back(), slots_[static_cast<std::size_t>(e)]->frames.stacked());
  }
  if (!bootstrap.empty()) {
    Eigen::MatrixXd raw(static_cast<Eigen::Index>(bootstrap.size()), in);
    for (std::size_t k = 0; k < bootstrap.size(); ++k) raw.row(static_cast<Eigen::Index>(k)) = bootstrap[k].second.transpose();
    Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> xr = norm.normalize(raw).cast<float>();
    const torch::Tensor v = value->forward(torch::from_blob(xr.data(), {xr.rows(), in}, torch::kFloat32)).contiguous();
    for (std::size_t k = 0; k < bootstrap.size(); ++k)
      r.next_value[static_cast<std::size_t>(bootstrap[k].first)] = v.data_ptr<float>()[k];
  }
  times_.inference += bootstrapping.seconds();
  return r;
}

}  // namespace mimic
