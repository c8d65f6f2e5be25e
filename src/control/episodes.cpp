#include "control/episodes.hpp"

#include <algorithm>
#include <cmath>
#include <deque>

#include "control/skill_impl.hpp"
#include "core/error.hpp"
#include "core/worker_pool.hpp"

namespace mimic {

namespace {

// One environment's running episode.
struct Slot {
  std::unique_ptr<Env> env;
  std::mt19937_64 rng;
  std::deque<Eigen::VectorXd> frames;  // the last `history` observations, oldest first
  double episode_return = 0.0;
  int episode_length = 0;
  bool idle = false;
  Eigen::VectorXd action;
  StepResult result;
};

}  // namespace

Rollout run_episodes(const Skill& skill, const EpisodeOptions& o, std::mt19937_64& noise_rng, EpisodeStats& stats) {
  if (o.episodes < 1 || o.slots < 1 || o.threads < 1)
    throw Error(skill.name() + ": episodes need episodes, slots and threads >= 1");
  const Skill::Impl& s = skill.impl();
  const int n_env = std::min(o.episodes, o.slots), frame = s.frame_size, in = skill.input_size(), na = s.action_size;
  if (o.fixed_action.size() > 0 && (o.fixed_action.size() != na || !o.fixed_action.allFinite()))
    throw Error(skill.name() + ": a fixed action of " + std::to_string(o.fixed_action.size()) + " finite values was given; the skill acts with " +
                std::to_string(na));
  // Each environment's generator, as the collector seeds its environments.
  std::seed_seq seq{o.seed, std::uint64_t{0x6d696d6963}};  // "mimic"
  std::vector<std::uint64_t> seeds(static_cast<std::size_t>(n_env));
  seq.generate(seeds.begin(), seeds.end());
  std::vector<Slot> slots(static_cast<std::size_t>(n_env));
  for (int e = 0; e < n_env; ++e) {
    slots[static_cast<std::size_t>(e)].env = s.factory();
    slots[static_cast<std::size_t>(e)].rng.seed(seeds[static_cast<std::size_t>(e)]);
  }
  auto check = [&](const Eigen::VectorXd& obs, int e, const std::string& when) {
    if (obs.size() != frame || !obs.allFinite())
      throw Error(skill.name() + ": environment " + std::to_string(e) + ": " + when + " gave a non-finite or wrongly sized observation");
  };
  auto start = [&](int e) {
    Slot& slot = slots[static_cast<std::size_t>(e)];
    const Eigen::VectorXd obs = slot.env->reset(slot.rng);
    check(obs, e, "reset");
    slot.frames.assign(static_cast<std::size_t>(s.history), obs);
    slot.episode_return = 0.0;
    slot.episode_length = 0;
  };
  WorkerPool pool(std::min(o.threads, n_env));
  // The collector starts every environment when it is built and again when its episodes begin:
  // the second starts are the episodes' (the first ones' draws are spent).
  pool.run(n_env, start);
  pool.run(n_env, start);

  Rollout r;
  r.input_size = in, r.frame_size = frame, r.action_size = na, r.envs = n_env;
  r.env_steps.resize(static_cast<std::size_t>(n_env));
  int started = n_env;
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::vector<int> active;
  for (;;) {
    active.clear();
    for (int e = 0; e < n_env; ++e)
      if (!slots[static_cast<std::size_t>(e)].idle) active.push_back(e);
    if (active.empty()) break;
    const auto b = static_cast<Eigen::Index>(active.size());
    Eigen::MatrixXd raw(b, in);
    for (Eigen::Index k = 0; k < b; ++k) {
      const Slot& slot = slots[static_cast<std::size_t>(active[static_cast<std::size_t>(k)])];
      for (int f = 0; f < s.history; ++f) raw.row(k).segment(f * frame, frame) = slot.frames[static_cast<std::size_t>(f)].transpose();
    }
    FloatMatrix mean(b, na);
    if (o.fixed_action.size() > 0) mean.rowwise() = o.fixed_action.cast<float>().transpose();
    else mean = s.policy.forward(s.normalised(raw));
    const std::size_t base = r.env_reward.size();
    for (Eigen::Index k = 0; k < b; ++k) {
      const int e = active[static_cast<std::size_t>(k)];
      Slot& slot = slots[static_cast<std::size_t>(e)];
      slot.action.resize(na);
      for (int j = 0; j < na; ++j) {
        const double mu = mean(k, j), ls = s.log_std[j];
        const double z = o.deterministic ? 0.0 : gauss(noise_rng);
        const auto a = static_cast<float>(mu + std::exp(ls) * z);
        slot.action[j] = a;
        r.action.push_back(a);
        r.mean.push_back(mean(k, j));
        r.log_std.push_back(s.log_std[j]);
      }
      for (int c = 0; c < in; ++c) r.raw_input.push_back(raw(k, c));
      r.env_steps[static_cast<std::size_t>(e)].push_back(static_cast<int>(base + static_cast<std::size_t>(k)));
      r.env_reward.push_back(0.0);
      r.ended.push_back(0);
      r.failed.push_back(0);
    }
    pool.run(static_cast<int>(b), [&](int k) {
      Slot& slot = slots[static_cast<std::size_t>(active[static_cast<std::size_t>(k)])];
      slot.result = slot.env->step(slot.action);
    });
    std::vector<int> to_reset;
    for (Eigen::Index k = 0; k < b; ++k) {
      const int e = active[static_cast<std::size_t>(k)];
      Slot& slot = slots[static_cast<std::size_t>(e)];
      const StepResult& res = slot.result;
      const std::size_t i = base + static_cast<std::size_t>(k);
      check(res.observation, e, "step " + std::to_string(slot.episode_length + 1) + " of its episode");
      const double reward = res.reward();
      if (!std::isfinite(reward))
        throw Error(skill.name() + ": environment " + std::to_string(e) + ": non-finite reward at step " + std::to_string(slot.episode_length + 1));
      r.env_reward[i] = reward;
      r.next_obs.insert(r.next_obs.end(), res.observation.data(), res.observation.data() + frame);
      slot.frames.pop_front();
      slot.frames.push_back(res.observation);
      slot.episode_return += reward;
      ++slot.episode_length;
      if (!res.done()) continue;
      r.ended[i] = 1;
      r.failed[i] = is_failure(res.termination) ? 1 : 0;
      stats.returns.push_back(slot.episode_return);
      stats.lengths.push_back(slot.episode_length);
      if (r.failed[i]) ++stats.failures;
      if (started >= o.episodes) {
        slot.idle = true;
      } else {
        ++started;
        to_reset.push_back(e);
      }
    }
    if (!to_reset.empty()) pool.run(static_cast<int>(to_reset.size()), [&](int k) { start(to_reset[static_cast<std::size_t>(k)]); });
  }
  return r;
}

}  // namespace mimic
