#include "learn/rewards/adversarial_reward.hpp"

#include <algorithm>
#include <filesystem>

#include "core/error.hpp"
#include "core/file_io.hpp"
#include "env/context_env.hpp"
#include "learn/networks/input_widening.hpp"
#include "learn/rewards/per_context_reward.hpp"

namespace mimic {

int TransitionFeatures::width() const {
  return transition == "s" ? state_width() : transition == "ss" ? 2 * state_width() : state_width() + action_size;
}

namespace {

// One state's features into row i from column `at`: the chosen entries, then the context.
template <class Vec>
void put_state(FeatureRows& out, int i, int at, const TransitionFeatures& f, const Vec& state) {
  const int c = static_cast<int>(f.columns.size());
  for (int k = 0; k < c; ++k) out(i, at + k) = static_cast<float>(state[f.columns[static_cast<std::size_t>(k)]]);
  for (int j = 0; j < f.contexts; ++j)
    out(i, at + c + j) = f.fixed_context >= 0 ? (j == f.fixed_context ? 1.0f : 0.0f) : static_cast<float>(state[f.context_offset + j]);
}

template <class Obs, class Next, class Act>
FeatureRows gather(int n, const TransitionFeatures& f, Obs obs, Next next, Act act) {
  FeatureRows out(n, f.width());
  const int w = f.state_width();
  for (int i = 0; i < n; ++i) {
    if (f.transition == "s") {
      put_state(out, i, 0, f, next(i));
      continue;
    }
    put_state(out, i, 0, f, obs(i));
    if (f.transition == "ss")
      put_state(out, i, w, f, next(i));
    else
      for (int k = 0; k < f.action_size; ++k) out(i, w + k) = static_cast<float>(act(i)[k]);
  }
  return out;
}

torch::Tensor to_tensor(const FeatureRows& m) {
  return torch::from_blob(const_cast<float*>(m.data()), {m.rows(), m.cols()}, torch::kFloat32).clone();
}

// The parts' rows one after another.
FeatureRows stacked(const std::vector<FeatureRows>& parts, int width) {
  Eigen::Index rows = 0;
  for (const auto& p : parts) rows += p.rows();
  FeatureRows out(rows, width);
  Eigen::Index at = 0;
  for (const auto& p : parts) out.middleRows(at, p.rows()) = p, at += p.rows();
  return out;
}

}  // namespace

FeatureRows TransitionFeatures::of(const Rollout& r) const {
  return gather(r.size(), *this, [&](int i) { return r.frame(i); }, [&](int i) { return r.next_frame(i); },
                [&](int i) { return r.action_of(i); });
}

FeatureRows TransitionFeatures::of(const Demonstrations& d) const {
  return gather(d.size(), *this, [&](int i) { return d.obs.row(i); }, [&](int i) { return d.next_obs.row(i); },
                [&](int i) { return d.action.row(i); });
}

std::vector<int> slice_columns(const std::vector<ObservationSlice>& layout, int frame_size, const std::vector<std::string>& names,
                               const std::string& where) {
  std::vector<int> cols;
  if (names.empty()) {
    for (int k = 0; k < frame_size; ++k) cols.push_back(k);
    return cols;
  }
  for (const auto& name : names) {
    const auto it = std::find_if(layout.begin(), layout.end(), [&](const ObservationSlice& s) { return s.name == name; });
    if (it == layout.end()) {
      std::string known;
      for (const auto& s : layout) known += (known.empty() ? "" : ", ") + s.name;
      throw Error(where + ": unknown observation part '" + name + "' (this environment has: " + known + ")");
    }
    for (int k = 0; k < it->size; ++k) cols.push_back(it->offset + k);
  }
  return cols;
}

AdversarialRewardSource::AdversarialRewardSource(std::string name, TransitionFeatures features, const FeatureRows& expert,
                                                 const DiscriminatorConfig& cfg, std::uint64_t seed)
    : name_(std::move(name)), features_(std::move(features)), disc_(to_tensor(expert), cfg, seed) {
  if (expert.cols() != features_.width()) throw Error("adversarial reward: expert and policy features differ in width");
}

std::vector<double> AdversarialRewardSource::rewards(const Rollout& rollout) {
  const torch::Tensor r = disc_.reward(to_tensor(features_.of(rollout))).to(torch::kFloat64).contiguous();
  std::vector<double> out(r.data_ptr<double>(), r.data_ptr<double>() + r.numel());
  last_reward_ = r.numel() > 0 ? r.mean().item<double>() : 0.0;
  return out;
}

std::vector<std::pair<std::string, double>> AdversarialRewardSource::update(const Rollout& rollout) {
  const DiscriminatorStats s = disc_.update(to_tensor(features_.of(rollout)));
  std::vector<std::pair<std::string, double>> m{{"reward", last_reward_},
                                                {"loss", s.loss},
                                                {"expert_accuracy", s.expert_accuracy},
                                                {"policy_accuracy", s.policy_accuracy},
                                                {"expert_score", s.expert_score},
                                                {"policy_score", s.policy_score}};
  if (disc_.config().gradient_penalty > 0) m.emplace_back("penalty", s.penalty);
  if (disc_.config().mismatched > 0 && disc_.mismatched().size(0) > 0) {
    m.emplace_back("mismatched_accuracy", s.mismatched_accuracy);
    m.emplace_back("mismatched_score", s.mismatched_score);
  }
  return m;
}

std::vector<double> AdversarialRewardSource::score(const Demonstrations& d, int context) {
  TransitionFeatures f = features_;
  if (f.contexts > 0 && (context < 0 || context >= f.contexts))
    throw Error(name_ + ": its discriminator takes a behaviour context: give one of 0 to " + std::to_string(f.contexts - 1));
  if (f.contexts == 0 && context >= 0) throw Error(name_ + ": its discriminator has no behaviour context");
  f.fixed_context = context;
  const int needed = f.columns.empty() ? 0 : *std::max_element(f.columns.begin(), f.columns.end()) + 1;
  if (d.obs.cols() < needed)
    throw Error(d.source + ": demonstrations have " + std::to_string(d.obs.cols()) + " observation values; " + name_ + "'s features read " +
                std::to_string(needed));
  if (f.transition == "sa" && d.action.cols() != f.action_size)
    throw Error(d.source + ": demonstrations have " + std::to_string(d.action.cols()) + " action values; " + name_ + " scores (s, a) with " +
                std::to_string(f.action_size));
  const torch::NoGradGuard no_grad;
  const torch::Tensor r = disc_.reward(to_tensor(f.of(d))).to(torch::kFloat64).contiguous();
  return {r.data_ptr<double>(), r.data_ptr<double>() + r.numel()};
}

void AdversarialRewardSource::save(torch::serialize::OutputArchive& a) const { disc_.save(a); }
void AdversarialRewardSource::load(torch::serialize::InputArchive& a) { disc_.load(a); }

void AdversarialRewardSource::load_widened(torch::serialize::InputArchive& a, int added_contexts) {
  if (features_.contexts == 0) {  // one expert file for every context: the discriminator's inputs did not change
    disc_.load(a);
    return;
  }
  if (features_.contexts != added_contexts)
    throw Error(name_ + ": its features hold " + std::to_string(features_.contexts) + " context inputs, not the " +
                std::to_string(added_contexts) + " the observation gained (give one demonstrations file per context: experts)");
  // The one-hot follows each state's entries; a (s, a) transition's action comes after them.
  const int states = features_.transition == "ss" ? 2 : 1;
  const std::int64_t saved_width = disc_.input_size() - static_cast<std::int64_t>(states) * added_contexts;
  disc_.load_widened(a, widened_columns(saved_width, static_cast<std::int64_t>(features_.columns.size()), states, added_contexts));
}

namespace {

// The expert file beside the config when it is there (a run or model directory holds its own
// demonstrations), else as given (absolute, or relative to the working directory).
std::filesystem::path find_expert(const std::string& given, const std::string& config_source) {
  const std::filesystem::path p(given), beside = std::filesystem::path(config_source).parent_path() / p;
  if (p.is_relative() && std::filesystem::exists(beside)) return beside;
  if (std::filesystem::exists(p)) return p;
  throw Error(config_source + ": expert demonstrations '" + given + "' not found (looked beside the config and in the working directory)");
}

}  // namespace

namespace {

// One demonstrations file's features by the policy's rule `f`: the same columns, or the named
// parts found in the file's own layout (an expert with another body); `fixed_context` for files
// of a behaviour context. Errors name the file.
FeatureRows expert_features(const std::string& path, const RewardSourceContext& context, const TransitionFeatures& f,
                            const std::vector<std::string>& names, int episodes, int fixed_context, const std::string& features_key) {
  Demonstrations demos = read_demonstrations(find_expert(path, context.config_source));
  TransitionFeatures ef = f;
  ef.fixed_context = fixed_context;
  const int own_size = context.frame_size - f.contexts;  // the observation without its context
  const bool by_layout = !names.empty() && !demos.layout.empty();
  if (by_layout) ef.columns = slice_columns(demos.layout, static_cast<int>(demos.obs.cols()), names, demos.source);
  if (!by_layout && demos.obs.cols() != own_size)
    throw Error(demos.source + ": demonstrations have " + std::to_string(demos.obs.cols()) + " observation values, the environment " +
                std::to_string(own_size) + ": for an expert with another body, name the shared observation parts in 'features' " +
                "(the demonstrations must name their layout, as mimic record writes it)");
  if (ef.columns.size() != f.columns.size())
    throw Error(demos.source + ": the features " + features_key + " name " + std::to_string(ef.columns.size()) + " expert values but " +
                std::to_string(f.columns.size()) + " of this environment");
  if (f.transition == "sa" && demos.action.cols() != context.action_size)
    throw Error(demos.source + ": demonstrations have " + std::to_string(demos.action.cols()) + " action values, the environment " +
                std::to_string(context.action_size) + ": imitate another body with transition s or ss");
  if (episodes > 0) {
    if (demos.episodes() < episodes)
      throw Error(demos.source + ": " + std::to_string(demos.episodes()) + " episodes, but 'episodes' asks for " + std::to_string(episodes));
    demos = demos.first_episodes(episodes);
  }
  return ef.of(demos);
}

}  // namespace

std::unique_ptr<RewardSource> make_adversarial_reward_source(const std::string& kind, ConfigSection& s, const YamlReader& reader,
                                                             const RewardSourceContext& context) {
  const bool iccgan = kind == "iccgan";
  DiscriminatorConfig d;
  if (iccgan) {  // seed 004 Table 1 and section 5.1
    d.loss = "hinge", d.heads = 32, d.gradient_penalty = 10.0, d.lr = 1e-5, d.batch = 512, d.replay = 8192;
    d.standardise = "mixture";  // seed 004 section 6.1: inputs normalised by statistics updated during training
    d.penalty_of = "sum";       // seed 004's released code; each head's own let the humanoid's reward go flat
    d.net.hidden = {256, 128};
    d.net.activation = "relu";
  }
  const std::string expert_path = s.text("expert", "");
  const std::vector<std::string> per_context = s.texts("experts", {});
  if (expert_path.empty() == per_context.empty())
    throw Error(context.config_source + ": give either " + s.name("expert") + " (a demonstrations file, from mimic record) or " +
                s.name("experts") + " (one file per behaviour context)");
  const int episodes = static_cast<int>(s.integer("episodes", 0, 0, 1'000'000));
  TransitionFeatures f;
  f.transition = s.choice("transition", iccgan ? "ss" : "s", {"s", "ss", "sa"});
  std::vector<std::string> names = s.texts("features", {});
  d.loss = s.choice("loss", d.loss, {"bce", "hinge"});
  d.heads = static_cast<int>(s.integer("heads", d.heads, 1, 1024));
  d.gradient_penalty = s.number("gradient_penalty", d.gradient_penalty, 0, 1e6);
  d.penalty_heads = static_cast<int>(s.integer("penalty_heads", d.penalty_heads, 0, 1024));
  d.penalty_of = s.choice("penalty_of", d.penalty_of, {"heads", "sum"});
  d.lr = s.number("lr", d.lr, 1e-12, 1);
  d.epochs = static_cast<int>(s.integer("epochs", d.epochs, 0, 1000));
  d.batch = static_cast<int>(s.integer("batch", d.batch, 1, 1 << 20));
  d.replay = static_cast<int>(s.integer("replay", d.replay, 0, 1 << 26));
  d.reward = s.choice("reward", d.reward, {"neg_log_one_minus_d", "log_d", "logit"});
  if (d.loss == "hinge" && s.has("reward"))
    throw Error(context.config_source + ": " + s.name("reward") + " is the bce discriminator's (GAIL); the hinge ensemble's reward is the mean of its clipped heads");
  d.reward_clip = s.number("reward_clip", d.reward_clip, 1e-6, 1e6);
  d.reward_offset = s.number("reward_offset", d.reward_offset, -1e6, 1e6);
  d.standardise = s.choice("standardise", d.standardise, {"expert", "mixture"});
  const bool separate = s.boolean("per_context", false);
  if (separate && per_context.empty())
    throw Error(context.config_source + ": " + s.name("per_context") + " needs " + s.name("experts") + " (one file per behaviour context)");
  d.mismatched = s.number("mismatched", 0.0, 0, 100);
  if (d.mismatched > 0 && per_context.empty())
    throw Error(context.config_source + ": " + s.name("mismatched") + " needs " + s.name("experts") + " (one file per behaviour context)");
  {
    ConfigSection n(reader, s.child("network"), s.name("network"));
    d.net = read_network(reader, n, d.net, false);  // a discriminator has no observation layout: no encoder
    n.finish();
  }
  s.finish();

  const std::string features_key = s.name("features");
  const std::string where = context.config_source + ": " + features_key;
  f.action_size = context.action_size;
  if (per_context.empty()) {
    f.columns = slice_columns(context.layout, context.frame_size, names, where);
    const FeatureRows expert = expert_features(expert_path, context, f, names, episodes, -1, features_key);
    return std::make_unique<AdversarialRewardSource>(kind, std::move(f), expert, d, context.seed);
  }
  // Behaviour contexts: the environment's context slice follows every state's chosen entries.
  const std::optional<ObservationSlice> ctx = context_slice(context.layout);
  if (!ctx || ctx->size != static_cast<int>(per_context.size()))
    throw Error(context.config_source + ": " + s.name("experts") + " names " + std::to_string(per_context.size()) +
                " files: the environment needs env.context with count " + std::to_string(per_context.size()));
  f.contexts = ctx->size;
  f.context_offset = ctx->offset;
  if (names.empty())
    for (const auto& p : context.layout)
      if (p.name != "context") names.push_back(p.name);
  f.columns = slice_columns(context.layout, context.frame_size, names, where);
  if (separate) {
    // One discriminator per context, each on the observation without its one-hot.
    TransitionFeatures own = f;
    own.contexts = 0, own.context_offset = -1;
    RewardSourceContext without = context;
    without.frame_size -= f.contexts;
    std::vector<FeatureRows> files;
    for (const auto& path : per_context) files.push_back(expert_features(path, without, own, names, episodes, -1, features_key));
    std::vector<std::unique_ptr<AdversarialRewardSource>> parts;
    for (std::size_t k = 0; k < files.size(); ++k) {
      parts.push_back(std::make_unique<AdversarialRewardSource>(kind, own, files[k], d, context.seed + k));
      if (d.mismatched > 0) {  // part k's mismatched samples: every other context's demonstrations
        std::vector<FeatureRows> others;
        for (std::size_t j = 0; j < files.size(); ++j)
          if (j != k) others.push_back(files[j]);
        parts.back()->discriminator().set_mismatched(to_tensor(stacked(others, own.width())));
      }
    }
    return std::make_unique<PerContextRewardSource>(kind, f.context_offset, std::move(parts));
  }
  // One discriminator with the one-hot among its inputs: file k under context k is expert; under
  // any other context, mismatched.
  std::vector<FeatureRows> matched, mismatched;
  for (std::size_t k = 0; k < per_context.size(); ++k)
    for (std::size_t j = 0; j < per_context.size(); ++j)
      if (j == k || d.mismatched > 0)
        (j == k ? matched : mismatched)
            .push_back(expert_features(per_context[k], context, f, names, episodes, static_cast<int>(j), features_key));
  auto source = std::make_unique<AdversarialRewardSource>(kind, f, stacked(matched, f.width()), d, context.seed);
  if (d.mismatched > 0) source->discriminator().set_mismatched(to_tensor(stacked(mismatched, f.width())));
  return source;
}

}  // namespace mimic
