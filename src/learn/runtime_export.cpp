#include "learn/runtime_export.hpp"


#include "core/file_io.hpp"
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

std::vector<double> to_vector(const Eigen::VectorXd& v) { return {v.data(), v.data() + v.size()}; }

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
  out.push_back(NamedArray::of_text("value.activation", t.cfg.value.activation));
  add_network(out, "value", *t.learner->value());
  return out;
}

void write_runtime_file(const Trainer::Impl& t, const std::filesystem::path& path) { write_file_atomic(path, encode_arrays(runtime_arrays(t))); }

}  // namespace mimic
