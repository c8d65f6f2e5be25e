#include "learn/trainer/train_config.hpp"

#include <algorithm>
#include <optional>
#include <thread>

#include "core/config_file.hpp"
#include "core/config_override.hpp"
#include "core/config_section.hpp"
#include "core/error.hpp"
#include "core/file_io.hpp"

namespace mimic {

namespace {

std::string flow_or_absent(const YAML::Node& n) { return !n.IsDefined() || n.IsNull() ? "absent" : flow_yaml(n); }

// The first key path at which `a` and `b` differ ("" at the top), or nullopt.
std::optional<std::string> first_difference(const YAML::Node& a, const YAML::Node& b, const std::string& path) {
  const bool a_absent = !a.IsDefined() || a.IsNull(), b_absent = !b.IsDefined() || b.IsNull();
  if (a_absent || b_absent) return a_absent == b_absent ? std::nullopt : std::optional(path);
  if (a.Type() != b.Type()) return path;
  const std::string prefix = path.empty() ? "" : path + ".";
  if (a.IsScalar()) return a.Scalar() == b.Scalar() ? std::nullopt : std::optional(path);
  if (a.IsSequence()) {
    if (a.size() != b.size()) return path;
    for (std::size_t i = 0; i < a.size(); ++i)
      if (auto d = first_difference(a[i], b[i], prefix + std::to_string(i))) return d;
    return std::nullopt;
  }
  std::vector<std::string> keys;
  for (const YAML::Node& m : {a, b})
    for (const auto& kv : m) {
      const std::string key = kv.first.as<std::string>();
      if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
    }
  for (const std::string& key : keys) {
    if (path == "collect" && key == "threads") continue;  // the same results with any thread count
    if (path.empty() && key == "iterations") continue;     // how far a run goes (mimic train --iterations)
    if (auto d = first_difference(a[key], b[key], prefix + key)) return d;
  }
  return std::nullopt;
}

YAML::Node node_at(YAML::Node n, const std::string& path) {
  std::size_t start = 0;
  while (!path.empty() && start <= path.size()) {
    const std::size_t dot = path.find('.', start);
    const std::string key = path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    YAML::Node next = n.IsSequence() ? n[std::stoul(key)] : n[key];
    n.reset(next);
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  return n;
}

constexpr long kMaxLayer = 1 << 16;
}  // namespace

NetworkConfig read_network(const YamlReader& r, ConfigSection& s, NetworkConfig n, bool encoder) {
  n.hidden = s.integers("hidden", n.hidden, 1, kMaxLayer);
  n.activation = s.choice("activation", n.activation, {"tanh", "relu"});
  n.init = s.choice("init", n.init, {"orthogonal", "truncated_normal"});
  n.init_std = s.number("init_std", n.init_std, 1e-9, 10);
  n.output_init = s.choice("output_init", n.output_init, {"orthogonal", "truncated_normal"});
  n.output_scale = s.number("output_scale", n.output_scale, 1e-9, 100);
  n.history = static_cast<int>(s.integer("history", n.history, 1, 64));
  n.gru_size = static_cast<int>(s.integer("gru_size", n.gru_size, 1, kMaxLayer));
  if (encoder && s.has("encoder")) {
    const YAML::Node node = s.child("encoder");
    const std::string quoted = s.name("encoder"), path = quoted.substr(1, quoted.size() - 2);
    ConfigSection e(r, node, path);
    n.encoder.input = e.text("input", "");
    if (n.encoder.input.empty()) r.fail(node, e.name("input") + " names the observation part the encoder reads (height_map, say)");
    n.encoder.hidden = e.integers("hidden", n.encoder.hidden, 1, kMaxLayer);
    if (n.encoder.hidden.empty()) r.fail(node, e.name("hidden") + " needs at least one layer");
    e.finish();
    if (n.history > 1) r.fail(node, quoted + " needs history 1 (it reads one frame's part)");
  }
  return n;
}

int resolve_threads(int requested) {
  return requested > 0 ? requested : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

TrainConfig parse_train_config(const std::string& text, const std::string& source) {
  const YamlReader r(source);
  const YAML::Node root = r.parse(text, "not valid YAML");
  if (!root.IsMap()) r.fail(root, "a training config is a mapping of sections (env, policy, ppo, ...)");
  TrainConfig c;
  c.source = source;
  c.text = text;
  ConfigSection top(r, root, "");
  c.seed = top.seed("seed", c.seed);
  c.iterations = static_cast<int>(top.integer("iterations", c.iterations, 1, 100'000'000));
  c.checkpoint_every = static_cast<int>(top.integer("checkpoint_every", c.checkpoint_every, 1, 100'000'000));
  c.snapshot_every = static_cast<int>(top.integer("snapshot_every", c.snapshot_every, 0, 100'000'000));
  c.tensorboard = top.boolean("tensorboard", c.tensorboard);
  c.env = top.child("env");
  if (c.env.IsDefined() && !c.env.IsMap()) r.fail(c.env, "'env': expected a mapping such as {name: planar_walker}");

  {
    ConfigSection p(r, top.child("policy"), "policy");
    c.policy.net = read_network(r, p, c.policy.net);
    c.policy.log_std = p.number("log_std", c.policy.log_std, -20, 5);
    c.policy.learn_std = p.boolean("learn_std", c.policy.learn_std);
    if (p.has("log_std_final")) {
      if (c.policy.learn_std) r.fail(top.child("policy"), "'policy.log_std_final' anneals a fixed covariance: set 'learn_std: false'");
      c.policy.log_std_final = p.number("log_std_final", 0.0, -20, 5);
    }
    p.finish();
  }
  {
    ConfigSection v(r, top.child("value"), "value");
    c.value = read_network(r, v, c.value);
    v.finish();
  }

  ConfigSection ppo(r, top.child("ppo"), "ppo");
  PpoConfig& o = c.ppo;
  o.gamma = ppo.number("gamma", o.gamma, 0, 1);
  o.lambda = ppo.number("lambda", o.lambda, 0, 1);
  o.clip = ppo.number("clip", o.clip, 0, 10);
  o.epochs = static_cast<int>(ppo.integer("epochs", o.epochs, 0, 10'000));
  o.value_epochs = static_cast<int>(ppo.integer("value_epochs", o.value_epochs, 0, 10'000));
  o.minibatch = static_cast<int>(ppo.integer("minibatch", o.minibatch, 1, 1'000'000));
  o.entropy = ppo.number("entropy", o.entropy, 0, 100);
  o.value_clip = ppo.number("value_clip", o.value_clip, 0, 1e9);
  o.max_grad_norm = ppo.number("max_grad_norm", o.max_grad_norm, 0, 1e9);
  o.kl_target = ppo.number("kl_target", o.kl_target, 0, 1e3);
  o.kl_penalty = ppo.boolean("kl_penalty", o.kl_penalty);
  o.kl_beta = ppo.number("kl_beta", o.kl_beta, 0, 1e6);
  o.kl_stop = ppo.number("kl_stop", o.kl_stop, 0, 1e6);
  o.normalize_advantages = ppo.boolean("normalize_advantages", o.normalize_advantages);
  ppo.finish();
  if ((o.kl_penalty || o.kl_stop > 0) && !(o.kl_target > 0))
    r.fail(root["ppo"], "'ppo.kl_target' must be positive when the KL penalty or early stop is on");

  ConfigSection opt(r, top.child("optimizer"), "optimizer");
  OptimizerConfig& op = c.optimizer;
  op.kind = opt.choice("kind", op.kind, {"adam", "sgd"});
  op.policy_lr = opt.number("policy_lr", op.policy_lr, 0, 10);
  op.value_lr = opt.number("value_lr", op.value_lr, 0, 10);
  op.momentum = opt.number("momentum", op.momentum, 0, 1);
  op.adam_epsilon = opt.number("adam_epsilon", op.adam_epsilon, 1e-20, 1);
  op.schedule = opt.choice("schedule", op.schedule, {"constant", "linear"});
  op.final_fraction = opt.number("final_fraction", op.final_fraction, 0, 1);
  opt.finish();

  ConfigSection col(r, top.child("collect"), "collect");
  CollectConfig& cc = c.collect;
  cc.envs = static_cast<int>(col.integer("envs", cc.envs, 1, 4096));
  cc.threads = static_cast<int>(col.integer("threads", cc.threads, 0, 1024));
  cc.samples = static_cast<int>(col.integer("samples", cc.samples, 1, 100'000'000));
  cc.mode = col.choice("mode", cc.mode, {"horizon", "episodes"});
  cc.episodes = static_cast<int>(col.integer("episodes", cc.episodes, 0, 10'000'000));
  cc.overlap = col.boolean("overlap", cc.overlap);
  col.finish();
  cc.threads = resolve_threads(cc.threads);
  if (cc.mode == "horizon" && cc.samples < cc.envs)
    r.fail(root["collect"], "'collect.samples' (" + std::to_string(cc.samples) + ") must be at least 'collect.envs' (" + std::to_string(cc.envs) + ")");
  if (cc.mode == "episodes" && cc.episodes < 1) r.fail(root["collect"], "'collect.episodes' must be >= 1 in episodes mode");

  ConfigSection norm(r, top.child("normalize"), "normalize");
  c.normalize.observations = norm.boolean("observations", c.normalize.observations);
  c.normalize.clip = norm.number("clip", c.normalize.clip, 0, 1e9);
  c.normalize.rewards = norm.boolean("rewards", c.normalize.rewards);
  norm.finish();

  ConfigSection init(r, top.child("init"), "init");
  c.init.kind = init.choice("kind", c.init.kind, {"env", "adaptive"});
  AdaptiveInitConfig& asi = c.init.adaptive;
  asi.components = static_cast<int>(init.integer("components", asi.components, 1, 10'000));
  asi.step = init.number("step", asi.step, 0, 1e3);
  asi.batch_episodes = static_cast<int>(init.integer("episodes", asi.batch_episodes, 1, 100'000'000));
  asi.std_scale = init.number("std_scale", asi.std_scale, 0, 1e3);
  asi.min_std = init.number("min_std", asi.min_std, 1e-9, 1e3);
  init.finish();

  const YAML::Node rewards = top.child("rewards");
  if (rewards.IsDefined()) {
    if (!rewards.IsSequence() || rewards.size() == 0) r.fail(rewards, "'rewards': expected a non-empty list of {source, weight}");
    c.rewards.clear();
    for (std::size_t i = 0; i < rewards.size(); ++i) {
      const std::string where = "rewards[" + std::to_string(i) + "]";
      if (!rewards[i].IsMap()) r.fail(rewards[i], "'" + where + "': expected a mapping with 'source'");
      RewardSourceConfig rs;
      rs.source = r.text(rewards[i], "source", "'" + where + "'");
      rs.weight = r.number_or(rewards[i], "weight", "'" + where + "'", 1.0);
      rs.options = rewards[i];
      c.rewards.push_back(rs);
    }
  }
  top.finish();
  return c;
}

std::string with_iterations(const std::string& text, const std::string& source, int n) {
  if (n < 1) throw Error(source + ": iterations must be at least 1, not " + std::to_string(n));
  const YamlReader r(source);
  const YAML::Node root = r.parse(text, "not valid YAML");
  if (!root.IsNull() && !root.IsMap()) r.fail(root, "a training config is a mapping of sections (env, policy, ppo, ...)");
  const YAML::Node current = root.IsMap() ? root["iterations"] : YAML::Node();
  if (current.IsDefined() && current.IsScalar() && current.Scalar() == std::to_string(n)) return text;
  if (!current.IsDefined() && n == TrainConfig{}.iterations) return text;  // asks for n by default
  const std::string line = "iterations: " + std::to_string(n);
  // A block-style top-level key starts its line: replace that line, whatever follows it.
  std::size_t at = 0;
  std::vector<std::size_t> starts;
  while (at < text.size()) {
    if (text.compare(at, 11, "iterations:") == 0) starts.push_back(at);
    const std::size_t end = text.find('\n', at);
    if (end == std::string::npos) break;
    at = end + 1;
  }
  if (starts.size() == 1) {
    const std::size_t end = text.find('\n', starts[0]);
    return text.substr(0, starts[0]) + line + (end == std::string::npos ? "\n" : text.substr(end));
  }
  if (starts.empty() && !current.IsDefined()) return text + (text.empty() || text.back() == '\n' ? "" : "\n") + line + "\n";
  return override_config(text, source, {"iterations=" + std::to_string(n)});
}

std::string config_difference(const std::string& first, const std::string& first_label, const std::string& second,
                              const std::string& second_label) {
  auto load = [](const std::string& text, const std::string& label) {
    try {
      return YAML::Load(text);
    } catch (const YAML::Exception& e) {
      throw Error(label + ": not valid YAML (" + e.msg + ")");
    }
  };
  const YAML::Node a = load(first, first_label), b = load(second, second_label);
  const std::optional<std::string> path = first_difference(a, b, "");
  if (!path) return "";
  return (path->empty() ? std::string("the whole config") : *path) + ": " + flow_or_absent(node_at(a, *path)) + " in " + first_label + ", " +
         flow_or_absent(node_at(b, *path)) + " in " + second_label;
}

TrainConfig load_train_config(const std::filesystem::path& path) {
  return parse_train_config(read_config_file(path), path.string());
}

}  // namespace mimic
