#include "learn/adversarial_reward.hpp"

#include <filesystem>

#include "core/error.hpp"
#include "core/file_io.hpp"

namespace mimic {

int TransitionFeatures::width() const {
  const int cols = static_cast<int>(columns.size());
  return transition == "s" ? cols : transition == "ss" ? 2 * cols : cols + action_size;
}

namespace {

template <class Obs, class Next, class Act>
FeatureRows gather(int n, const TransitionFeatures& f, Obs obs, Next next, Act act) {
  FeatureRows out(n, f.width());
  const int c = static_cast<int>(f.columns.size());
  for (int i = 0; i < n; ++i) {
    if (f.transition == "s") {
      for (int k = 0; k < c; ++k) out(i, k) = static_cast<float>(next(i)[f.columns[static_cast<std::size_t>(k)]]);
      continue;
    }
    for (int k = 0; k < c; ++k) out(i, k) = static_cast<float>(obs(i)[f.columns[static_cast<std::size_t>(k)]]);
    if (f.transition == "ss")
      for (int k = 0; k < c; ++k) out(i, c + k) = static_cast<float>(next(i)[f.columns[static_cast<std::size_t>(k)]]);
    else
      for (int k = 0; k < f.action_size; ++k) out(i, c + k) = static_cast<float>(act(i)[k]);
  }
  return out;
}

torch::Tensor to_tensor(const FeatureRows& m) {
  return torch::from_blob(const_cast<float*>(m.data()), {m.rows(), m.cols()}, torch::kFloat32).clone();
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

AdversarialRewardSource::AdversarialRewardSource(std::string name, TransitionFeatures features, const TransitionFeatures& expert_features,
                                                 const Demonstrations& expert, const DiscriminatorConfig& cfg, std::uint64_t seed)
    : name_(std::move(name)), features_(std::move(features)), disc_(to_tensor(expert_features.of(expert)), cfg, seed) {
  if (expert_features.width() != features_.width()) throw Error(expert.source + ": expert and policy features differ in width");
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
  return m;
}

void AdversarialRewardSource::save(torch::serialize::OutputArchive& a) const { disc_.save(a); }
void AdversarialRewardSource::load(torch::serialize::InputArchive& a) { disc_.load(a); }

namespace {

// The expert file as given (relative to the working directory), else beside the config.
std::filesystem::path find_expert(const std::string& given, const std::string& config_source) {
  const std::filesystem::path p(given);
  if (std::filesystem::exists(p)) return p;
  const std::filesystem::path beside = std::filesystem::path(config_source).parent_path() / p;
  if (!p.is_absolute() && std::filesystem::exists(beside)) return beside;
  throw Error(config_source + ": expert demonstrations '" + given + "' not found (looked in the working directory and beside the config)");
}

}  // namespace

std::unique_ptr<RewardSource> make_adversarial_reward_source(const std::string& kind, ConfigSection& s, const YamlReader& reader,
                                                             const RewardSourceContext& context) {
  const bool iccgan = kind == "iccgan";
  DiscriminatorConfig d;
  if (iccgan) {  // seed 004 Table 1 and section 5.1
    d.loss = "hinge", d.heads = 32, d.gradient_penalty = 10.0, d.lr = 1e-5, d.batch = 512, d.replay = 8192;
    d.net.hidden = {256, 128};
    d.net.activation = "relu";
  }
  const std::string expert_path = s.text("expert", "");
  if (expert_path.empty()) throw Error(context.config_source + ": " + s.name("expert") + " is required: a demonstrations file (mimic record)");
  const int episodes = static_cast<int>(s.integer("episodes", 0, 0, 1'000'000));
  TransitionFeatures f;
  f.transition = s.choice("transition", iccgan ? "ss" : "s", {"s", "ss", "sa"});
  const std::vector<std::string> names = s.texts("features", {});
  d.loss = s.choice("loss", d.loss, {"bce", "hinge"});
  d.heads = static_cast<int>(s.integer("heads", d.heads, 1, 1024));
  d.gradient_penalty = s.number("gradient_penalty", d.gradient_penalty, 0, 1e6);
  d.lr = s.number("lr", d.lr, 1e-12, 1);
  d.epochs = static_cast<int>(s.integer("epochs", d.epochs, 0, 1000));
  d.batch = static_cast<int>(s.integer("batch", d.batch, 1, 1 << 20));
  d.replay = static_cast<int>(s.integer("replay", d.replay, 0, 1 << 26));
  d.reward_clip = s.number("reward_clip", d.reward_clip, 1e-6, 1e6);
  d.reward_offset = s.number("reward_offset", d.reward_offset, -1e6, 1e6);
  {
    ConfigSection n(reader, s.child("network"), s.name("network"));
    d.net = read_network(n, d.net);
    n.finish();
  }
  s.finish();

  const std::string where = context.config_source + ": " + s.name("features");
  f.columns = slice_columns(context.layout, context.frame_size, names, where);
  f.action_size = context.action_size;
  Demonstrations demos = read_demonstrations(find_expert(expert_path, context.config_source));
  // The expert's columns: by name in the demonstrations' own layout (another body), else the same.
  TransitionFeatures ef = f;
  const bool by_layout = !names.empty() && !demos.layout.empty();
  if (by_layout) ef.columns = slice_columns(demos.layout, static_cast<int>(demos.obs.cols()), names, demos.source);
  if (!by_layout && demos.obs.cols() != context.frame_size)
    throw Error(demos.source + ": demonstrations have " + std::to_string(demos.obs.cols()) + " observation values, the environment " +
                std::to_string(context.frame_size) + ": for an expert with another body, name the shared observation parts in 'features' " +
                "(the demonstrations must name their layout, as mimic record writes it)");
  if (ef.columns.size() != f.columns.size())
    throw Error(demos.source + ": the features " + s.name("features") + " name " + std::to_string(ef.columns.size()) + " expert values but " +
                std::to_string(f.columns.size()) + " of this environment");
  if (f.transition == "sa" && demos.action.cols() != context.action_size)
    throw Error(demos.source + ": demonstrations have " + std::to_string(demos.action.cols()) + " action values, the environment " +
                std::to_string(context.action_size) + ": imitate another body with transition s or ss");
  if (episodes > 0) {
    if (demos.episodes() < episodes)
      throw Error(demos.source + ": " + std::to_string(demos.episodes()) + " episodes, but " + s.name("episodes") + " asks for " +
                  std::to_string(episodes));
    demos = demos.first_episodes(episodes);
  }
  return std::make_unique<AdversarialRewardSource>(kind, std::move(f), ef, demos, d, context.seed);
}

}  // namespace mimic
