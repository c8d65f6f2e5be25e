#include "learn/networks/runtime_export.hpp"


#include "core/file_io.hpp"
#include "learn/rewards/adversarial_reward.hpp"
#include "learn/rewards/per_context_reward.hpp"
#include "sim/mujoco_load.hpp"

namespace mimic {

namespace {

void add_network(std::vector<NamedArray>& out, const std::string& prefix, const torch::nn::Module& m) {
  for (const auto& p : m.named_parameters()) {
    const torch::Tensor t = p.value().detach().to(torch::kFloat32).contiguous();
    std::vector<std::uint32_t> shape;
    for (const std::int64_t d : t.sizes()) shape.push_back(static_cast<std::uint32_t>(d));
    const float* v = t.data_ptr<float>();
    out.push_back(NamedArray::of_floats(prefix + "." + p.key(), shape, std::vector<float>(v, v + t.numel())));
  }
}

// Where an encoder's part lies in the network's input (its layers are "<prefix>.encoder.K.*").
void add_encoder_place(std::vector<NamedArray>& out, const std::string& prefix, const EncoderConfig& e) {
  if (!e.enabled()) return;
  out.push_back(NamedArray::of_scalar(prefix + ".encoder_offset", e.offset));
  out.push_back(NamedArray::of_scalar(prefix + ".encoder_size", e.size));
}

std::vector<double> to_vector(const Eigen::VectorXd& v) { return {v.data(), v.data() + v.size()}; }

std::vector<float> floats_of(const torch::Tensor& t) {
  const torch::Tensor c = t.detach().to(torch::kFloat32).contiguous();
  return {c.data_ptr<float>(), c.data_ptr<float>() + c.numel()};
}

// One discriminator under "discriminator.<index>.": what it reads of a transition, how it
// standardises it, its network and how its outputs become a reward (docs/runtime.md).
void add_discriminator(std::vector<NamedArray>& out, int index, const std::string& source, int context, const AdversarialRewardSource& a) {
  const std::string p = "discriminator." + std::to_string(index) + ".";
  const TransitionFeatures& f = a.features();
  const Discriminator& d = const_cast<AdversarialRewardSource&>(a).discriminator();
  const DiscriminatorConfig& c = d.config();
  out.push_back(NamedArray::of_text(p + "source", source));
  out.push_back(NamedArray::of_scalar(p + "context", context));
  out.push_back(NamedArray::of_text(p + "transition", f.transition));
  std::vector<double> columns(f.columns.begin(), f.columns.end());
  out.push_back(NamedArray::of_doubles(p + "columns", {static_cast<std::uint32_t>(columns.size())}, columns));
  out.push_back(NamedArray::of_scalar(p + "contexts", f.contexts));
  out.push_back(NamedArray::of_scalar(p + "context_offset", f.context_offset));
  out.push_back(NamedArray::of_text(p + "loss", c.loss));
  out.push_back(NamedArray::of_text(p + "reward", c.reward));
  out.push_back(NamedArray::of_scalar(p + "reward_clip", c.reward_clip));
  out.push_back(NamedArray::of_scalar(p + "reward_offset", c.reward_offset));
  const auto width = static_cast<std::uint32_t>(d.input_size());
  out.push_back(NamedArray::of_floats(p + "input_mean", {width}, floats_of(d.input_mean().reshape({-1}))));
  out.push_back(NamedArray::of_floats(p + "input_std", {width}, floats_of(d.input_std().reshape({-1}))));
  out.push_back(NamedArray::of_scalar(p + "history", c.net.history));
  out.push_back(NamedArray::of_text(p + "activation", c.net.activation));
  add_network(out, p + "net", *d.net());
}

}  // namespace

std::vector<NamedArray> runtime_arrays(const Trainer::Impl& t) {
  const int input = t.collector->input_size(), history = t.cfg.policy.net.history;
  std::vector<NamedArray> out;
  out.push_back(NamedArray::of_text("format", kRuntimeFormat));
  out.push_back(NamedArray::of_scalar("iteration", t.iteration));
  out.push_back(NamedArray::of_scalar("samples", static_cast<double>(t.samples)));
  std::string layout;
  for (const ObservationSlice& s : t.layout) layout += s.name + " " + std::to_string(s.offset) + " " + std::to_string(s.size) + "\n";
  out.push_back(NamedArray::of_text("observation.layout", layout));
  out.push_back(NamedArray::of_scalar("observation.frame_size", t.collector->frame_size()));
  out.push_back(NamedArray::of_scalar("observation.history", history));
  out.push_back(NamedArray::of_scalar("action_size", t.collector->action_size()));
  const auto n = static_cast<std::uint32_t>(input);
  out.push_back(NamedArray::of_scalar("observation.count", t.obs_norm.count()));
  out.push_back(NamedArray::of_doubles("observation.mean", {n}, to_vector(t.obs_norm.mean())));
  out.push_back(NamedArray::of_doubles("observation.variance", {n}, to_vector(t.obs_norm.variance())));
  out.push_back(NamedArray::of_scalar("observation.epsilon", t.obs_norm.epsilon()));
  out.push_back(NamedArray::of_scalar("observation.clip", t.obs_norm.clip()));
  // The character the networks act on: its MuJoCo bodies, in order (a world must have the same;
  // projectiles and other bodies an environment adds are not the character's).
  {
    const std::unique_ptr<Env> probe = t.factory();
    std::string bodies;
    for (const std::string& name : character_body_names(probe->physics_model())) bodies += name + "\n";
    out.push_back(NamedArray::of_text("character.bodies", bodies));
  }
  out.push_back(NamedArray::of_text("policy.activation", t.cfg.policy.net.activation));
  add_network(out, "policy", *t.learner->policy());
  add_encoder_place(out, "policy.net", t.cfg.policy.net.encoder);
  out.push_back(NamedArray::of_text("value.activation", t.cfg.value.activation));
  add_network(out, "value", *t.learner->value());
  add_encoder_place(out, "value.net", t.cfg.value.encoder);
  // The discriminators of the adversarial reward sources, in the config's order (one per
  // behaviour context where each context has its own); none where the run was loaded without them.
  int discriminators = 0;
  for (const auto& entry : t.rewards) {
    RewardSource* r = entry.second.get();
    if (auto* separate = dynamic_cast<PerContextRewardSource*>(r))
      for (int k = 0; k < separate->contexts(); ++k) add_discriminator(out, discriminators++, separate->name(), k, separate->part(k));
    else if (auto* adversarial = dynamic_cast<AdversarialRewardSource*>(r))
      add_discriminator(out, discriminators++, adversarial->name(), -1, *adversarial);
  }
  out.push_back(NamedArray::of_scalar("discriminator.count", discriminators));
  return out;
}

void write_runtime_file(const Trainer::Impl& t, const std::filesystem::path& path) { write_file_atomic(path, encode_arrays(runtime_arrays(t))); }

}  // namespace mimic
