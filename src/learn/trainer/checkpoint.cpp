// Checkpoints: one LibTorch archive holding the networks, both optimizers (Adam moments or SGD
// momentum), normalisers, the KL penalty, every random generator, counters and the config text.
// Written to memory, then atomically to disk; read back with errors naming the file.
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <sstream>

#include "core/error.hpp"
#include "core/file_io.hpp"
#include "core/zip_integrity.hpp"
#include "learn/networks/archive_util.hpp"
#include "learn/networks/input_widening.hpp"
#include "learn/rewards/per_context_reward.hpp"
#include "learn/trainer/ranks.hpp"
#include "learn/trainer/trainer_impl.hpp"

namespace mimic {

namespace {

constexpr std::int64_t kFormat = 1;
using torch::serialize::InputArchive;
using torch::serialize::OutputArchive;
using namespace archive;

void write_normalizer(OutputArchive& a, const std::string& key, const RunningNormalizer& n) {
  OutputArchive sub;
  sub.write("count", torch::tensor(n.count(), torch::kFloat64));
  sub.write("mean", vec_tensor(n.mean()));
  sub.write("m2", vec_tensor(n.m2()));
  a.write(key, sub);
}
void read_normalizer(InputArchive& a, const std::string& key, RunningNormalizer& n) {
  InputArchive sub;
  a.read(key, sub);
  n.set_state(get(sub, "count").item<double>(), tensor_vec(get(sub, "mean")), tensor_vec(get(sub, "m2")));
}

// ASI's parameters, its pending episodes and its step count (exact resume).
OutputArchive adaptive_init_archive(const Trainer::Impl& t) {
  const AdaptiveInit& d = *t.adaptive_init;
  auto flat = [](const Eigen::MatrixXd& m) { return vec_tensor(Eigen::Map<const Eigen::VectorXd>(m.data(), m.size())); };
  OutputArchive o;
  o.write("means", flat(d.means()));
  o.write("log_std", flat(d.log_std()));
  o.write("updates", torch::tensor(static_cast<std::int64_t>(t.init_updates)));
  const auto n = static_cast<Eigen::Index>(t.init_pending.size());
  Eigen::VectorXd component(n), ret(n);
  Eigen::MatrixXd x(d.dims(), n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto& p = t.init_pending[static_cast<std::size_t>(i)];
    component[i] = p.component, ret[i] = p.ret, x.col(i) = p.x;
  }
  o.write("pending_component", vec_tensor(component));
  o.write("pending_return", vec_tensor(ret));
  o.write("pending_x", flat(x));
  return o;
}

void read_adaptive_init(Trainer::Impl& t, InputArchive& a) {
  AdaptiveInit& d = *t.adaptive_init;
  const Eigen::Index k = d.components(), dims = d.dims();
  auto matrix = [&](const std::string& key, Eigen::Index rows, Eigen::Index cols) {
    const Eigen::VectorXd v = tensor_vec(get(a, key));
    if (v.size() != rows * cols) throw Error("adaptive_init." + key + ": " + std::to_string(v.size()) + " values, expected " + std::to_string(rows * cols));
    return Eigen::MatrixXd(Eigen::Map<const Eigen::MatrixXd>(v.data(), rows, cols));
  };
  d.set_parameters(matrix("means", k, dims), matrix("log_std", k, dims));
  t.init_updates = static_cast<int>(get(a, "updates").item<std::int64_t>());
  const Eigen::VectorXd component = tensor_vec(get(a, "pending_component")), ret = tensor_vec(get(a, "pending_return"));
  const Eigen::MatrixXd x = matrix("pending_x", dims, component.size());
  t.init_pending.clear();
  for (Eigen::Index i = 0; i < component.size(); ++i)
    t.init_pending.push_back({static_cast<int>(component[i]), x.col(i), ret[i]});
}
}  // namespace

std::string serialize_checkpoint(const Trainer::Impl& t) {
  t.learner->check_parameters(t.iteration);  // never save a broken model
  for (const auto& [weight, source] : t.rewards) {
    try {
      source->check_weights();
    } catch (const TrainingDiverged& e) {
      throw TrainingDiverged("iteration " + std::to_string(t.iteration) + ", reward source '" + source->name() + "', " + e.what());
    }
  }
  OutputArchive a;
  a.write("format", torch::tensor(kFormat));
  a.write("iteration", torch::tensor(static_cast<std::int64_t>(t.iteration)));
  a.write("samples", torch::tensor(static_cast<std::int64_t>(t.samples)));
  a.write("wall_seconds", torch::tensor(t.wall_seconds, torch::kFloat64));
  a.write("config", bytes_tensor(t.cfg.text));
  if (t.acting_only) a.write("acting_only", torch::tensor(static_cast<std::int64_t>(1)));
  a.write("input_size", torch::tensor(static_cast<std::int64_t>(t.collector->input_size())));
  a.write("action_size", torch::tensor(static_cast<std::int64_t>(t.collector->action_size())));
  OutputArchive policy, value, policy_opt, value_opt, rngs, sources;
  t.learner->policy()->save(policy);
  t.learner->value()->save(value);
  t.learner->policy_optimizer().save(policy_opt);
  t.learner->value_optimizer().save(value_opt);
  a.write("policy", policy);
  a.write("value", value);
  a.write("policy_optimizer", policy_opt);
  a.write("value_optimizer", value_opt);
  a.write("kl_beta", torch::tensor(t.learner->kl().beta(), torch::kFloat64));
  write_normalizer(a, "obs_norm", t.obs_norm);
  write_normalizer(a, "return_norm", t.return_norm);
  rngs.write("noise", bytes_tensor(rng_text(t.noise_rng)));
  rngs.write("shuffle", bytes_tensor(rng_text(t.shuffle_rng)));
  const auto env_states = t.collector->rng_states();
  rngs.write("envs", torch::tensor(static_cast<std::int64_t>(env_states.size())));
  for (std::size_t i = 0; i < env_states.size(); ++i) rngs.write("env" + std::to_string(i), bytes_tensor(env_states[i]));
  if (ranks::many()) {  // every rank's generators, in rank 0's file (the others' copy is not written)
    const std::vector<std::string> all = ranks::gather(generator_state(t));
    rngs.write("ranks", torch::tensor(static_cast<std::int64_t>(ranks::size())));
    for (std::size_t k = 1; k < all.size(); ++k) rngs.write("rank" + std::to_string(k), bytes_tensor(all[k]));
  }
  a.write("rng", rngs);
  for (std::size_t i = 0; i < t.rewards.size(); ++i) {
    OutputArchive s;
    t.rewards[i].second->save(s);
    sources.write(std::to_string(i), s);
  }
  a.write("reward_sources", sources);
  if (t.adaptive_init) {
    OutputArchive asi = adaptive_init_archive(t);
    a.write("adaptive_init", asi);
  }
  std::ostringstream out;
  a.save_to(out);
  return out.str();
}

void write_policy_snapshot(const Trainer::Impl& t, const std::filesystem::path& path) {
  OutputArchive a, policy;
  a.write("format", torch::tensor(kFormat));
  a.write("policy_snapshot", torch::tensor(static_cast<std::int64_t>(1)));
  a.write("iteration", torch::tensor(static_cast<std::int64_t>(t.iteration)));
  a.write("samples", torch::tensor(static_cast<std::int64_t>(t.samples)));
  a.write("wall_seconds", torch::tensor(t.wall_seconds, torch::kFloat64));
  a.write("config", bytes_tensor(t.cfg.text));
  a.write("input_size", torch::tensor(static_cast<std::int64_t>(t.collector->input_size())));
  a.write("action_size", torch::tensor(static_cast<std::int64_t>(t.collector->action_size())));
  t.learner->policy()->save(policy);
  a.write("policy", policy);
  write_normalizer(a, "obs_norm", t.obs_norm);
  std::ostringstream out;
  a.save_to(out);
  write_file_atomic(path, out.str());
}

namespace {

// Opens the archive after the checks LibTorch does not make; errors without the file's name.
void open_archive(const std::filesystem::path& path, InputArchive& a) {
  const std::string bytes = read_text_file(path, kMaxCheckpointBytes);
  // LibTorch's archives are zip files; anything else is refused here (LibTorch's zip reader
  // leaks memory on non-zip input, and "not a zip archive" says more).
  if (bytes.size() < 22 || bytes.compare(0, 4, "PK\x03\x04") != 0)
    throw Error("not a mimic checkpoint (not a LibTorch zip archive" + std::string(bytes.empty() ? ": empty file" : "") + ")");
  // A cut file (an interrupted copy, a full disk) has lost the zip's closing directory record.
  const std::size_t tail = bytes.size() > 65557 ? bytes.size() - 65557 : 0;
  if (bytes.rfind("PK\x05\x06") == std::string::npos || bytes.rfind("PK\x05\x06") < tail)
    throw Error("checkpoint is truncated (its zip directory is missing): " + std::to_string(bytes.size()) + " bytes");
  // LibTorch never checks the CRC-32s its archives record: a flipped bit in the weights would load.
  try {
    verify_zip(bytes);
  } catch (const Error& e) {
    throw Error(std::string("checkpoint is damaged, nothing of it was used (") + e.what() + ")");
  }
  std::istringstream in(bytes);
  a.load_from(in);
}

std::string size_mismatch(const Trainer::Impl& t, std::int64_t in_size, std::int64_t act_size) {
  return "saved for an input of " + std::to_string(in_size) + " and " + std::to_string(act_size) + " actions; the config's environment has " +
         std::to_string(t.collector->input_size()) + " and " + std::to_string(t.collector->action_size());
}

// A checkpoint of another format version would fail later with LibTorch's message about some key.
void check_format(InputArchive& a) {
  const auto format = get(a, "format").item<std::int64_t>();
  if (format != kFormat) throw Error("checkpoint format " + std::to_string(format) + ", this mimic reads " + std::to_string(kFormat));
}

// Opens a checkpoint for this trainer: a readable archive of this format, saved for the same
// action size and (unless `other_input_ok`) input size, and not a policy snapshot unless
// `snapshot_ok`; returns the saved input size.
std::int64_t open_for(const Trainer::Impl& t, const std::filesystem::path& path, InputArchive& a, bool other_input_ok = false,
                      bool snapshot_ok = false) {
  open_archive(path, a);
  check_format(a);
  torch::Tensor flag;
  if (!snapshot_ok && a.try_read("policy_snapshot", flag))
    throw Error("a policy snapshot (the policy's weights and normaliser, for mimic export --average-last), not a checkpoint");
  const auto in_size = get(a, "input_size").item<std::int64_t>();
  const auto act_size = get(a, "action_size").item<std::int64_t>();
  if ((in_size != t.collector->input_size() && !other_input_ok) || act_size != t.collector->action_size())
    throw Error(size_mismatch(t, in_size, act_size));
  return in_size;
}

// Context inputs the observation gained since `saved_config` (a run without a behaviour
// context, now with one): the size of the env's context slice when the input grew by exactly one
// per stacked frame, else 0.
int added_context_inputs(Trainer::Impl& t, const YAML::Node& saved_config, std::int64_t saved_input) {
  const YAML::Node saved_context = saved_config["env"] ? saved_config["env"]["context"] : YAML::Node();
  if (saved_context && saved_context["count"] && saved_context["count"].as<int>() > 0) return 0;
  for (const ObservationSlice& s : t.collector->env(0).observation_layout()) {
    if (s.name != "context") continue;
    const std::int64_t frames = t.collector->input_size() / t.collector->frame_size();
    return saved_input + frames * s.size == t.collector->input_size() ? s.size : 0;
  }
  return 0;
}

// The observation parts this config added to those of the saved run (rebuilt from its config's
// env for its layout), and where each saved input now lies; an Error where a saved part is
// missing, resized or moved. No names: nothing was added, or `why_not` says why it cannot tell
// (the saved env could not be rebuilt, or its input is not its layout's).
struct AddedParts {
  std::vector<std::string> names;
  std::vector<std::int64_t> kept;
  std::string why_not;
};
AddedParts added_observation_parts(const Trainer::Impl& t, const std::string& where, const YAML::Node& saved_config,
                                   std::int64_t saved_input) {
  std::vector<ObservationSlice> saved_layout;
  try {
    if (!saved_config["env"]) return {{}, {}, "its config names no environment"};
    saved_layout = make_env_factory(saved_config["env"], YamlReader(where + "'s config"))()->observation_layout();
  } catch (const std::exception& e) {
    return {{}, {}, std::string("its environment could not be rebuilt to compare observations: ") + e.what()};
  }
  const std::int64_t frames = t.collector->input_size() / t.collector->frame_size();
  std::int64_t saved_width = 0;
  for (const ObservationSlice& s : saved_layout) saved_width += s.size;
  if (saved_width * frames != saved_input) return {{}, {}, "its policy stacks another number of frames"};
  AddedParts added;
  added.kept = mapped_columns(saved_layout, t.layout, frames);
  for (const ObservationSlice& s : t.layout)
    if (std::none_of(saved_layout.begin(), saved_layout.end(), [&](const ObservationSlice& o) { return o.name == s.name; }))
      added.names.push_back(s.name);
  return added;
}

// The saved normaliser's statistics at their new places; a new input starts at `mean` and
// `variance` over the saved count (a context's: those of contexts drawn evenly, 1/K and
// (1/K)(1 - 1/K); another part's: 0 and 1, its raw value, as a long run's count barely moves).
void read_widened_normalizer(InputArchive& a, const std::string& key, RunningNormalizer& n, const std::vector<std::int64_t>& kept,
                             double mean, double variance) {
  InputArchive sub;
  a.read(key, sub);
  const double count = get(sub, "count").item<double>();
  n.set_state(count, tensor_vec(widen_columns(get(sub, "mean"), kept, n.size(), mean)),
              tensor_vec(widen_columns(get(sub, "m2"), kept, n.size(), count * variance)));
}

// `read(archive)` on the opened checkpoint at `path`, every failure an Error naming the file.
template <class F>
auto read_archive(const std::filesystem::path& path, F&& read) {
  try {
    InputArchive a;
    open_archive(path, a);
    return read(a);
  } catch (const c10::Error& e) {
    throw Error(path.string() + ": not a readable mimic checkpoint (" + std::string(e.what_without_backtrace()) + ")");
  } catch (const Error& e) {
    throw Error(path.string() + ": " + e.what());
  } catch (const std::exception& e) {  // LibTorch's TorchScript reader throws kinds of its own
    throw Error(path.string() + ": not a readable mimic checkpoint (" + std::string(e.what()) + ")");
  }
}

}  // namespace

bool is_exported_checkpoint(const std::filesystem::path& path) {
  return read_archive(path, [](InputArchive& a) {
    torch::Tensor flag;
    return a.try_read("acting_only", flag);
  });
}

int checkpoint_iteration(const std::filesystem::path& path) {
  return read_archive(path, [](InputArchive& a) {
    check_format(a);
    return static_cast<int>(get(a, "iteration").item<std::int64_t>());
  });
}

void read_checkpoint(Trainer::Impl& t, const std::filesystem::path& path) {
  const std::string where = path.string();
  if (!std::filesystem::exists(path)) throw Error(where + ": no such checkpoint");
  try {
    InputArchive a;
    open_for(t, path, a);
    torch::Tensor acting_only;
    t.acting_only = a.try_read("acting_only", acting_only);
    t.iteration = static_cast<int>(get(a, "iteration").item<std::int64_t>());
    t.samples = get(a, "samples").item<std::int64_t>();
    t.wall_seconds = get(a, "wall_seconds").item<double>();
    InputArchive policy, value, policy_opt, value_opt, rngs, sources;
    a.read("policy", policy);
    a.read("value", value);
    a.read("policy_optimizer", policy_opt);
    a.read("value_optimizer", value_opt);
    t.learner->policy()->load(policy);
    t.learner->value()->load(value);
    t.learner->policy_optimizer().load(policy_opt);
    t.learner->value_optimizer().load(value_opt);
    t.learner->kl().set_beta(get(a, "kl_beta").item<double>());
    read_normalizer(a, "obs_norm", t.obs_norm);
    read_normalizer(a, "return_norm", t.return_norm);
    a.read("rng", rngs);
    set_rng(t.noise_rng, tensor_bytes(get(rngs, "noise")), "noise");
    set_rng(t.shuffle_rng, tensor_bytes(get(rngs, "shuffle")), "shuffle");
    std::vector<std::string> env_states(static_cast<std::size_t>(get(rngs, "envs").item<std::int64_t>()));
    for (std::size_t i = 0; i < env_states.size(); ++i) env_states[i] = tensor_bytes(get(rngs, "env" + std::to_string(i)));
    t.collector->set_rng_states(env_states);
    torch::Tensor saved_ranks, own;
    t.saved_ranks = rngs.try_read("ranks", saved_ranks) ? static_cast<int>(saved_ranks.item<std::int64_t>()) : 1;
    if (ranks::rank() > 0) {
      if (t.saved_ranks == ranks::size() && rngs.try_read("rank" + std::to_string(ranks::rank()), own)) set_generator_state(t, tensor_bytes(own));
      else reseed_generators(t);
    }
    a.read("reward_sources", sources);
    for (std::size_t i = 0; i < t.rewards.size(); ++i) {
      InputArchive s;
      sources.read(std::to_string(i), s);
      t.rewards[i].second->load(s);
    }
    if (t.adaptive_init) {
      InputArchive asi;
      a.read("adaptive_init", asi);
      read_adaptive_init(t, asi);
    }
    t.learner->check_parameters(t.iteration);
  } catch (const c10::Error& e) {
    throw Error(where + ": not a readable mimic checkpoint (" + std::string(e.what_without_backtrace()) + ")");
  } catch (const TrainingDiverged& e) {
    throw Error(where + ": " + e.what());
  } catch (const Error& e) {
    throw Error(where + ": " + e.what());
  } catch (const std::exception& e) {  // LibTorch's TorchScript reader throws kinds of its own
    throw Error(where + ": not a readable mimic checkpoint (" + std::string(e.what()) + ")");
  }
  // Fresh episodes from the restored generators, exactly as the saving run continued.
  t.collector->reset_all();
  std::fill(t.discounted_return.begin(), t.discounted_return.end(), 0.0);
}

int read_weights(Trainer::Impl& t, const std::filesystem::path& path) {
  const std::string where = path.string();
  if (!std::filesystem::exists(path)) throw Error(where + ": no such checkpoint");
  int sources_loaded = 0;
  try {
    InputArchive a;
    const std::int64_t saved_input = open_for(t, path, a, /*other_input_ok=*/true);
    const YAML::Node saved_config = YAML::Load(tensor_bytes(get(a, "config")));
    // A single-behaviour run may start a context run, and any run one whose observation gained
    // parts: its inputs widen, the new ones weigh zero.
    int added = 0;
    std::vector<std::int64_t> kept;
    double new_mean = 0.0, new_variance = 1.0;
    if (saved_input != t.collector->input_size()) {
      added = added_context_inputs(t, saved_config, saved_input);
      if (added > 0) {
        const std::int64_t frames = t.collector->input_size() / t.collector->frame_size();
        kept = widened_columns(saved_input, saved_input / frames, frames, added);
        t.contexts_added_by_init = added;
        new_mean = 1.0 / added, new_variance = new_mean * (1.0 - new_mean);
      } else {
        AddedParts parts = added_observation_parts(t, where, saved_config, saved_input);
        if (parts.names.empty())
          throw Error(size_mismatch(t, saved_input, t.collector->action_size()) + (parts.why_not.empty() ? "" : " (" + parts.why_not + ")"));
        kept = std::move(parts.kept);
        t.parts_added_by_init = std::move(parts.names);
      }
    } else {
      added_observation_parts(t, where, saved_config, saved_input);  // an error where the same parts are reordered
    }
    InputArchive policy, value, sources;
    a.read("policy", policy);
    a.read("value", value);
    if (kept.empty()) {
      t.learner->policy()->load(policy);
      t.learner->value()->load(value);
      read_normalizer(a, "obs_norm", t.obs_norm);
    } else {
      load_widened(*t.learner->policy(), policy, kept, t.collector->input_size());
      load_widened(*t.learner->value(), value, kept, t.collector->input_size());
      read_widened_normalizer(a, "obs_norm", t.obs_norm, kept, new_mean, new_variance);
    }
    read_normalizer(a, "return_norm", t.return_norm);
    // A fixed covariance is the config's choice, not the checkpoint's.
    if (!t.cfg.policy.learn_std) t.learner->policy()->set_log_std(t.cfg.policy.log_std);
    // A source's state goes to the source of the same kind at the same place in the list.
    const YAML::Node saved_rewards = saved_config["rewards"];
    a.read("reward_sources", sources);
    for (std::size_t i = 0; i < t.rewards.size() && saved_rewards && i < saved_rewards.size(); ++i) {
      const YAML::Node kind = saved_rewards[i]["source"];
      if ((kind ? kind.as<std::string>() : std::string("env")) != t.cfg.rewards[i].source) continue;
      InputArchive s;
      if (!sources.try_read(std::to_string(i), s) || s.keys().empty()) continue;  // the env's has no state
      if (added == 0)
        t.rewards[i].second->load(s);
      else
        t.rewards[i].second->load_widened(s, added);
      ++sources_loaded;
    }
    t.learner->check_parameters(0);
  } catch (const YAML::Exception& e) {
    throw Error(where + ": its saved config does not parse (" + std::string(e.what()) + ")");
  } catch (const c10::Error& e) {
    throw Error(where + ": cannot start from this checkpoint (" + std::string(e.what_without_backtrace()) + ")");
  } catch (const TrainingDiverged& e) {
    throw Error(where + ": " + e.what());
  } catch (const Error& e) {
    throw Error(where + ": " + e.what());
  } catch (const std::exception& e) {  // LibTorch's TorchScript reader throws kinds of its own
    throw Error(where + ": not a readable mimic checkpoint (" + std::string(e.what()) + ")");
  }
  return sources_loaded;
}

int read_context_discriminators(Trainer::Impl& t, const std::vector<std::filesystem::path>& checkpoints) {
  int sources = 0;
  for (std::size_t i = 0; i < t.rewards.size(); ++i) {
    auto* per_context = dynamic_cast<PerContextRewardSource*>(t.rewards[i].second.get());
    if (!per_context) continue;
    if (static_cast<int>(checkpoints.size()) != per_context->contexts())
      throw Error(per_context->name() + ": " + std::to_string(per_context->contexts()) + " behaviour contexts, " +
                  std::to_string(checkpoints.size()) + " runs to start their discriminators from (one per context, in context order)");
    for (std::size_t k = 0; k < checkpoints.size(); ++k) {
      const std::string where = checkpoints[k].string();
      if (!std::filesystem::exists(checkpoints[k])) throw Error(where + ": no such checkpoint");
      try {
        InputArchive a, saved_sources, s;
        open_archive(checkpoints[k], a);
        check_format(a);
        const YAML::Node saved_rewards = YAML::Load(tensor_bytes(get(a, "config")))["rewards"];
        const YAML::Node kind = saved_rewards && i < saved_rewards.size() ? saved_rewards[i]["source"] : YAML::Node();
        if (!kind || kind.as<std::string>() != t.cfg.rewards[i].source)
          throw Error("its reward source " + std::to_string(i) + " is not of kind '" + t.cfg.rewards[i].source + "', which context " +
                      std::to_string(k) + "'s part of " + per_context->name() + " needs");
        if (saved_rewards[i]["per_context"] && saved_rewards[i]["per_context"].as<bool>())
          throw Error("its reward source " + std::to_string(i) + " has one discriminator per context; context " + std::to_string(k) +
                      "'s part starts from a single behaviour's discriminator");
        a.read("reward_sources", saved_sources);
        saved_sources.read(std::to_string(i), s);
        per_context->part(static_cast<int>(k)).load(s);
      } catch (const YAML::Exception& e) {
        throw Error(where + ": its saved config does not parse (" + std::string(e.what()) + ")");
      } catch (const c10::Error& e) {
        throw Error(where + ": cannot start context " + std::to_string(k) + "'s discriminator from it (" + std::string(e.what_without_backtrace()) + ")");
      } catch (const Error& e) {
        throw Error(where + ": " + e.what());
      } catch (const std::exception& e) {  // LibTorch's TorchScript reader throws kinds of its own
        throw Error(where + ": not a readable mimic checkpoint (" + std::string(e.what()) + ")");
      }
    }
    ++sources;
  }
  if (sources == 0) throw Error("no reward source with one discriminator per context (per_context: true) to start from other runs");
  return sources;
}

namespace {

// The policy saved in `a` (a checkpoint or snapshot for this config), in a network of its own;
// an error unless it has this config's shapes and finite weights.
GaussianPolicy saved_policy(const Trainer::Impl& t, InputArchive& a) {
  InputArchive saved;
  a.read("policy", saved);
  GaussianPolicy policy(static_cast<int>(t.collector->input_size()), static_cast<int>(t.collector->action_size()), t.cfg.policy);
  policy->load(saved);  // LibTorch takes the saved shapes as they are: compared here
  const auto own = t.learner->policy()->named_parameters();
  const auto theirs = policy->named_parameters();
  for (std::size_t i = 0; i < own.size(); ++i)
    if (i >= theirs.size() || theirs[i].key() != own[i].key() || !theirs[i].value().sizes().equals(own[i].value().sizes()))
      throw Error("its policy's '" + own[i].key() + "' does not have this config's shape: not the same network");
  for (const auto& p : theirs)
    if (!torch::isfinite(p.value()).all().item<bool>()) throw Error("its policy's '" + p.key() + "' holds NaN or infinity");
  return policy;
}

}  // namespace

double average_policy(Trainer::Impl& t, const std::vector<std::filesystem::path>& checkpoints) {
  torch::NoGradGuard no_grad;
  const auto own = t.learner->policy()->named_parameters();
  std::vector<torch::Tensor> sum;
  for (const auto& p : own) sum.push_back(p.value().detach().clone());
  const Eigen::ArrayXd stddev = t.obs_norm.stddev().array().max(1e-8);
  double largest_shift = 0;
  for (const auto& path : checkpoints) {
    const std::string where = path.string();
    if (!std::filesystem::exists(path)) throw Error(where + ": no such checkpoint");
    try {
      InputArchive a;
      open_for(t, path, a, /*other_input_ok=*/false, /*snapshot_ok=*/true);
      const auto theirs = saved_policy(t, a)->named_parameters();
      for (std::size_t i = 0; i < own.size(); ++i) sum[i] += theirs[i].value();
      RunningNormalizer saved_norm(t.obs_norm.size());
      read_normalizer(a, "obs_norm", saved_norm);
      largest_shift = std::max(largest_shift, ((saved_norm.mean() - t.obs_norm.mean()).array().abs() / stddev).maxCoeff());
    } catch (const c10::Error& e) {
      throw Error(where + ": cannot average its policy (" + std::string(e.what_without_backtrace()) + ")");
    } catch (const Error& e) {
      throw Error(where + ": " + e.what());
    } catch (const std::exception& e) {  // LibTorch's TorchScript reader throws kinds of its own
      throw Error(where + ": not a readable mimic checkpoint (" + std::string(e.what()) + ")");
    }
  }
  const double n = static_cast<double>(checkpoints.size() + 1);
  for (std::size_t i = 0; i < own.size(); ++i) own[i].value().copy_(sum[i] / n);
  return largest_shift;
}

void read_policy(Trainer::Impl& t, const std::filesystem::path& path) {
  const std::string where = path.string();
  if (!std::filesystem::exists(path)) throw Error(where + ": no such checkpoint");
  torch::NoGradGuard no_grad;
  try {
    InputArchive a;
    open_for(t, path, a, /*other_input_ok=*/false, /*snapshot_ok=*/true);
    const auto theirs = saved_policy(t, a)->named_parameters();
    RunningNormalizer norm(t.obs_norm.size(), t.obs_norm.clip(), t.obs_norm.epsilon());
    read_normalizer(a, "obs_norm", norm);
    const auto iteration = get(a, "iteration").item<std::int64_t>();
    const auto samples = get(a, "samples").item<std::int64_t>();
    torch::Tensor wall;
    const bool has_wall = a.try_read("wall_seconds", wall);
    // All read and checked: only now does this trainer change, so that an error leaves it as it was.
    const auto own = t.learner->policy()->named_parameters();
    for (std::size_t i = 0; i < own.size(); ++i) own[i].value().copy_(theirs[i].value());
    t.obs_norm = norm;
    t.iteration = static_cast<int>(iteration);
    t.samples = samples;
    if (has_wall) t.wall_seconds = wall.item<double>();
  } catch (const c10::Error& e) {
    throw Error(where + ": cannot take its policy (" + std::string(e.what_without_backtrace()) + ")");
  } catch (const Error& e) {
    throw Error(where + ": " + e.what());
  } catch (const std::exception& e) {  // LibTorch's TorchScript reader throws kinds of its own
    throw Error(where + ": not a readable mimic checkpoint (" + std::string(e.what()) + ")");
  }
}

}  // namespace mimic
