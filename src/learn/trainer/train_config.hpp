#pragma once
// Every hyper-parameter of a PPO run, read from YAML. Defaults follow seed 002's Walker2d table
// (A.3) where it speaks; unknown keys and wrong types are errors naming the key.
#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "core/config_override.hpp"

namespace mimic {

// Seed 002's perceptual encoder (section 3.1.2, after Heess et al. 2016): one part of the
// observation (the height map ahead, say) goes through its own tanh MLP, whose last layer's
// outputs join the rest of the observation at the network's first layer.
struct EncoderConfig {
  std::string input;                  // the observation part's name; empty: no encoder
  std::vector<int> hidden{30, 40, 100};  // seed 002 Table A.4
  // Where the part lies in the network's input: resolved from the environment's layout
  // (resolve_encoder, learn/networks/networks.hpp), not a config key.
  int offset = -1, size = 0;
  bool enabled() const { return !input.empty(); }
};

struct NetworkConfig {
  std::vector<int> hidden{64, 64};
  std::string activation = "tanh";        // tanh | relu
  std::string init = "orthogonal";        // hidden layers: orthogonal | truncated_normal
  double init_std = 0.05;                 // truncated normal's std (seed 004: 0.05)
  std::string output_init = "orthogonal"; // orthogonal | truncated_normal
  double output_scale = 1.0;              // orthogonal gain or truncated normal std of the output layer
  int history = 1;                        // frames seen; > 1 embeds the last K frames with a GRU
  int gru_size = 256;                     // seed 004: GRU(256)
  EncoderConfig encoder;                  // none by default; needs history 1
};

struct PolicyConfig {
  PolicyConfig() { net.output_scale = 0.01; }  // small initial actions (the value head keeps 1)
  NetworkConfig net;
  double log_std = -1.0;   // initial log sigma (seed 002: -1; seed 000: e^-1..1)
  bool learn_std = true;   // false: fixed diagonal covariance (SFV)
  // With a fixed covariance: log sigma at the last iteration, reached linearly from log_std over
  // the run (NaN: held at log_std). Coarse exploration early, precise tracking late.
  double log_std_final = std::numeric_limits<double>::quiet_NaN();
};

struct PpoConfig {
  double gamma = 0.99, lambda = 0.95;
  double clip = 0.2;                 // surrogate clip range epsilon
  int epochs = 10;                   // policy epochs per iteration
  int value_epochs = 10;
  int minibatch = 64;
  double entropy = 0.0;              // entropy bonus weight
  double value_clip = 0.0;           // 0: unclipped value loss
  double max_grad_norm = 0.5;        // 0: no gradient-norm clipping
  double kl_target = 0.01;
  bool kl_penalty = false;           // adaptive beta (halve / double around the target)
  double kl_beta = 1.0;              // its initial value
  double kl_stop = 4.0;              // stop policy epochs when KL > kl_stop * target (0: never)
  bool normalize_advantages = true;
};

struct OptimizerConfig {
  std::string kind = "adam";         // adam | sgd (with momentum)
  double policy_lr = 3e-4, value_lr = 1e-3;
  double momentum = 0.9;             // sgd
  double adam_epsilon = 1e-8;
  std::string schedule = "constant"; // constant | linear (to final_fraction at the last iteration)
  double final_fraction = 0.0;
};

struct CollectConfig {
  int envs = 8;                 // environments stepped together
  int threads = 1;              // worker threads (0: every core)
  int samples = 4096;           // per iteration (horizon mode: samples / envs steps of each)
  std::string mode = "horizon"; // horizon | episodes
  int episodes = 0;             // episodes mode: complete episodes per iteration
  // Collect iteration k+1 with iteration k's policy while the learner learns from iteration k's
  // samples (one iteration of lag, corrected by PPO's ratio to the acting policy): learning no
  // longer adds to the wall time. Not across a checkpoint, so that a resumed run matches.
  bool overlap = false;
};

struct NormalizeConfig {
  bool observations = true;
  double clip = 10.0;
  bool rewards = false;  // divide rewards by the running std of discounted returns (seed 002)
};

// Seed 003's adaptive state initialisation (learn/imitation/adaptive_init.hpp).
struct AdaptiveInitConfig {
  int components = 10;        // k (seed 003 compares 5, 10, 20)
  double step = 0.1;          // natural-gradient step (learn/imitation/adaptive_init.hpp)
  int batch_episodes = 2000;  // episodes per gradient step
  double std_scale = 1.0;     // initial sigma = the clip's sample std * std_scale
  double min_std = 1e-3;
};

// Where training episodes start: the environment's own choice (`env`), or ASI (`adaptive`).
struct InitConfig {
  std::string kind = "env";
  AdaptiveInitConfig adaptive;
};

// One reward source and its weight; the trainer sums weight * reward over the sources.
struct RewardSourceConfig {
  std::string source = "env";  // env: the environment's task reward
  double weight = 1.0;
  YAML::Node options;          // the source's own keys
};

struct TrainConfig {
  std::uint64_t seed = 1;
  int iterations = 100;
  int checkpoint_every = 10;
  int snapshot_every = 0;  // > 0: the policy's weights to RUN/snapshots every that many iterations
  bool tensorboard = true;
  YAML::Node env;  // given to make_env_factory (env/env_factory.hpp); may be absent when the
                   // program supplies its own environments (TrainOptions::env_factory)
  PolicyConfig policy;
  NetworkConfig value;
  PpoConfig ppo;
  OptimizerConfig optimizer;
  CollectConfig collect;
  NormalizeConfig normalize;
  InitConfig init;
  std::vector<RewardSourceConfig> rewards{RewardSourceConfig{}};
  std::string source;  // where it came from (file path or label), for messages
  std::string text;    // the YAML as read, stored with checkpoints
};

class ConfigSection;
class YamlReader;
// A network's keys (hidden, activation, init, ...) from one config section; absent keys keep `defaults`.
// `encoder`: whether the section may hold an encoder (networks over an observation do).
NetworkConfig read_network(const YamlReader& r, ConfigSection& s, NetworkConfig defaults, bool encoder = true);

// Worker threads for a requested count: 0 means every core.
int resolve_threads(int requested);

// Parses YAML text; `source` names it in errors (ParseError: "source:line: 'ppo.clip': ...").
TrainConfig parse_train_config(const std::string& text, const std::string& source);
TrainConfig load_train_config(const std::filesystem::path& path);
// override_config (--set): core/config_override.hpp.

// The config text with its top-level `iterations` set to n, comments and layout kept: the line
// `iterations: ...` is replaced (or one added), or, for a config that names it some other way
// (flow style), the text is re-emitted as override_config does. The text itself when it already
// asks for n (also by leaving the default). How a run's config.yaml records the count the run goes
// to (`mimic train --iterations`), so that a plain `--resume` goes on to the same count.
std::string with_iterations(const std::string& text, const std::string& source, int n);

// Where two configs differ in what they ask for — comments, layout, the iteration count and
// collect.threads (neither changes what a checkpoint holds) aside: "rewards.0.features: [links,
// link_velocities] in run/config.yaml, [links] in walk.yaml", each config named by its label;
// empty when they agree. Bad YAML is an Error naming its label.
std::string config_difference(const std::string& first, const std::string& first_label, const std::string& second,
                              const std::string& second_label);

}  // namespace mimic
