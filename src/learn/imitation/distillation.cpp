#include "learn/imitation/distillation.hpp"

#include <algorithm>

#include "core/error.hpp"
#include "core/statistics.hpp"
#include "env/context_env.hpp"
#include "learn/trainer/trainer_impl.hpp"

namespace mimic {

Demonstrations label_by_teachers(const Demonstrations& states, const std::vector<ObservationSlice>& layout,
                                 const std::vector<PolicyFunction>& teachers) {
  const std::optional<ObservationSlice> ctx = context_slice(layout);
  const int contexts = ctx ? ctx->size : 0;
  if (static_cast<int>(teachers.size()) != std::max(contexts, 1))
    throw Error("distillation: " + std::to_string(teachers.size()) + " teachers for a student " +
                (contexts ? "with " + std::to_string(contexts) + " behaviour contexts (one teacher per context)"
                          : std::string("without behaviour contexts (one teacher)")));
  const Eigen::Index width = states.obs.cols();
  if (contexts && ctx->offset + ctx->size > width)
    throw Error("distillation: the context slice lies outside the student's " + std::to_string(width) + " observation values");
  Demonstrations out = states;
  Eigen::VectorXd input(width - contexts);
  for (Eigen::Index i = 0; i < states.obs.rows(); ++i) {
    const Eigen::VectorXd row = states.obs.row(i).transpose();
    int k = 0;
    if (contexts) {
      const Eigen::VectorXd one_hot = row.segment(ctx->offset, contexts);
      one_hot.maxCoeff(&k);
      if (one_hot[k] != 1.0 || one_hot.sum() != 1.0)
        throw Error("distillation: state " + std::to_string(i) + "'s context is not a one-hot");
      input << row.head(ctx->offset), row.tail(width - ctx->offset - contexts);
    } else {
      input = row;
    }
    const Eigen::VectorXd a = teachers[static_cast<std::size_t>(k)](input);
    if (a.size() != out.action.cols())
      throw Error("distillation: teacher " + std::to_string(k) + " gives " + std::to_string(a.size()) + " action values, the student " +
                  std::to_string(out.action.cols()));
    out.action.row(i) = a.transpose();
  }
  return out;
}

namespace {

// Only the newest `keep` rows (every per-row member, so that the set stays consistent).
void keep_newest(Demonstrations& d, int keep) {
  const Eigen::Index extra = d.obs.rows() - keep;
  if (extra <= 0) return;
  d.obs = d.obs.bottomRows(keep).eval();
  d.action = d.action.bottomRows(keep).eval();
  d.next_obs = d.next_obs.bottomRows(keep).eval();
  d.episode.erase(d.episode.begin(), d.episode.begin() + extra);
}

}  // namespace

void distill(Trainer& student, const std::vector<PolicyFunction>& teachers, const DistillOptions& o,
             const std::function<bool(const DistillRound&)>& after_round) {
  if (o.rounds < 1 || o.episodes < 1 || o.keep < 1 || o.epochs < 1 || o.batch < 1 || !(o.lr > 0) || o.first_round < 1)
    throw Error("distillation: rounds, episodes, keep, epochs, batch and learning rate must be positive");
  const std::vector<ObservationSlice>& layout = student.observation_layout();
  Demonstrations kept;
  long long samples = o.samples_before;
  for (int round = o.first_round; round <= o.rounds; ++round) {
    // The student's own states (sampled actions: DAgger's on-policy distribution, widened by its noise).
    const std::uint64_t seed = o.seed * 1'000'003 + static_cast<std::uint64_t>(round);
    EpisodeStats stats;
    const Demonstrations visited = impl_of(student).record(o.episodes, /*deterministic=*/false, seed, stats);
    samples += visited.size();
    kept.append(label_by_teachers(visited, layout, teachers));
    keep_newest(kept, o.keep);
    DistillRound r;
    r.round = round;
    r.samples = samples;
    r.kept = kept.size();
    r.episode_return = mean_of(stats.returns);
    std::vector<double> lengths(stats.lengths.begin(), stats.lengths.end());
    r.episode_length = mean_of(lengths);
    r.falls = stats.failures;
    r.loss = student.clone_behaviour(kept, o.epochs, o.lr, o.batch, seed);
    if (!after_round(r)) return;
  }
}

}  // namespace mimic
