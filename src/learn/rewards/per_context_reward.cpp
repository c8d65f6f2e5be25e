#include "learn/rewards/per_context_reward.hpp"

#include <torch/serialize.h>

#include <limits>

#include "core/error.hpp"

namespace mimic {

Rollout rollout_rows(const Rollout& r, const std::vector<int>& rows) {
  Rollout out;
  out.input_size = r.input_size, out.frame_size = r.frame_size, out.action_size = r.action_size, out.envs = 1;
  const auto in = static_cast<std::size_t>(r.input_size), frame = static_cast<std::size_t>(r.frame_size),
             act = static_cast<std::size_t>(r.action_size);
  out.raw_input.reserve(rows.size() * in);
  out.next_obs.reserve(rows.size() * frame);
  out.action.reserve(rows.size() * act);
  for (int i : rows) {
    const auto k = static_cast<std::size_t>(i);
    out.raw_input.insert(out.raw_input.end(), r.raw_input.begin() + static_cast<std::ptrdiff_t>(k * in),
                         r.raw_input.begin() + static_cast<std::ptrdiff_t>((k + 1) * in));
    out.next_obs.insert(out.next_obs.end(), r.next_obs.begin() + static_cast<std::ptrdiff_t>(k * frame),
                        r.next_obs.begin() + static_cast<std::ptrdiff_t>((k + 1) * frame));
    out.action.insert(out.action.end(), r.action.begin() + static_cast<std::ptrdiff_t>(k * act),
                      r.action.begin() + static_cast<std::ptrdiff_t>((k + 1) * act));
    out.env_reward.push_back(r.env_reward[k]);
  }
  return out;
}

PerContextRewardSource::PerContextRewardSource(std::string name, int context_offset, std::vector<std::unique_ptr<AdversarialRewardSource>> parts)
    : name_(std::move(name)), context_offset_(context_offset), parts_(std::move(parts)), metric_names_(parts_.size()) {
  if (parts_.size() < 2) throw Error(name_ + ": one discriminator per context needs at least 2 contexts");
  if (context_offset_ < 0) throw Error(name_ + ": no context in the observation");
}

std::vector<std::vector<int>> PerContextRewardSource::rows_by_context(const Rollout& r) const {
  std::vector<std::vector<int>> rows(parts_.size());
  for (int i = 0; i < r.size(); ++i) {
    const auto frame = r.frame(i);
    int c = 0;
    for (int k = 1; k < contexts(); ++k)
      if (frame[context_offset_ + k] > frame[context_offset_ + c]) c = k;
    rows[static_cast<std::size_t>(c)].push_back(i);
  }
  return rows;
}

std::vector<double> PerContextRewardSource::rewards(const Rollout& rollout) {
  std::vector<double> out(static_cast<std::size_t>(rollout.size()), 0.0);
  const auto rows = rows_by_context(rollout);
  for (std::size_t k = 0; k < parts_.size(); ++k) {
    if (rows[k].empty()) continue;
    const std::vector<double> part = parts_[k]->rewards(rollout_rows(rollout, rows[k]));
    for (std::size_t j = 0; j < rows[k].size(); ++j) out[static_cast<std::size_t>(rows[k][j])] = part[j];
  }
  return out;
}

std::vector<std::pair<std::string, double>> PerContextRewardSource::update(const Rollout& rollout) {
  std::vector<std::pair<std::string, double>> out;
  const auto rows = rows_by_context(rollout);
  for (std::size_t k = 0; k < parts_.size(); ++k) {
    const std::string suffix = "_c" + std::to_string(k);
    if (rows[k].empty()) {  // no sample of this context in the iteration: the same columns, unknown
      for (const auto& n : metric_names_[k]) out.emplace_back(n + suffix, std::numeric_limits<double>::quiet_NaN());
      continue;
    }
    metric_names_[k].clear();
    for (const auto& [n, v] : parts_[k]->update(rollout_rows(rollout, rows[k]))) {
      metric_names_[k].push_back(n);
      out.emplace_back(n + suffix, v);
    }
  }
  return out;
}

void PerContextRewardSource::drop_training_state() {
  for (auto& p : parts_) p->drop_training_state();
}

void PerContextRewardSource::save(torch::serialize::OutputArchive& a) const {
  for (std::size_t k = 0; k < parts_.size(); ++k) {
    torch::serialize::OutputArchive sub;
    parts_[k]->save(sub);
    a.write(std::to_string(k), sub);
  }
}

void PerContextRewardSource::load(torch::serialize::InputArchive& a) {
  for (std::size_t k = 0; k < parts_.size(); ++k) {
    torch::serialize::InputArchive sub;
    if (!a.try_read(std::to_string(k), sub))
      throw Error(name_ + ": the saved state has no discriminator for context " + std::to_string(k) +
                  " (saved without per_context: start this run from scratch)");
    parts_[k]->load(sub);
  }
}

void PerContextRewardSource::load_widened(torch::serialize::InputArchive& a, int added_contexts) {
  if (added_contexts != contexts())
    throw Error(name_ + ": " + std::to_string(contexts()) + " discriminators for the " + std::to_string(added_contexts) + " contexts added");
  for (auto& p : parts_) p->load(a);
}

std::vector<double> PerContextRewardSource::score(const Demonstrations& d, int context) {
  if (context < 0 || context >= contexts())
    throw Error(name_ + ": one discriminator per context: give a behaviour context 0 to " + std::to_string(contexts() - 1));
  return parts_[static_cast<std::size_t>(context)]->score(d, -1);
}

}  // namespace mimic
