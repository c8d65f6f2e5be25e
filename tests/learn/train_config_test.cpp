// Training configs: defaults, every section read, and errors that name the key and the line.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <iostream>

#include "control/navigation.hpp"
#include "core/config_section.hpp"
#include "core/error.hpp"
#include "core/file_io.hpp"
#include "core/yaml_reader.hpp"
#include "env/env_factory.hpp"
#include "learn/trainer/train_config.hpp"

using namespace mimic;

namespace {
// The message of the ParseError `text` raises (fails the test when it parses).
std::string error_of(const std::string& text) {
  try {
    (void)parse_train_config(text, "run.yaml");
  } catch (const ParseError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return "";
}
}  // namespace

TEST(TrainConfig, ReadsEverySection) {
  const TrainConfig c = parse_train_config(
      "seed: 7\niterations: 3\ncheckpoint_every: 2\ntensorboard: false\n"
      "env: {name: planar_walker, max_steps: 50}\n"
      "policy: {hidden: [32, 16], activation: relu, init: truncated_normal, init_std: 0.1, output_scale: 0.02,\n"
      "         log_std: -2, learn_std: false, history: 4, gru_size: 8}\n"
      "value: {hidden: [8], history: 4}\n"
      "ppo: {gamma: 0.95, lambda: 0.9, clip: 0.1, epochs: 3, value_epochs: 2, minibatch: 32, entropy: 0.001,\n"
      "      value_clip: 0.2, max_grad_norm: 1, kl_target: 0.02, kl_penalty: true, kl_beta: 3, kl_stop: 0}\n"
      "optimizer: {kind: sgd, policy_lr: 2.5e-6, value_lr: 0.01, momentum: 0.8, schedule: linear, final_fraction: 0.1}\n"
      "collect: {envs: 4, threads: 2, samples: 64, mode: episodes, episodes: 10}\n"
      "normalize: {observations: false, clip: 5, rewards: true}\n"
      "rewards: [{source: env, weight: 0.5}]\n",
      "test");
  EXPECT_EQ(c.seed, 7u);
  EXPECT_EQ(c.iterations, 3);
  EXPECT_EQ(c.checkpoint_every, 2);
  EXPECT_FALSE(c.tensorboard);
  EXPECT_EQ(c.env["max_steps"].as<int>(), 50);
  EXPECT_EQ(c.policy.net.hidden, (std::vector<int>{32, 16}));
  EXPECT_EQ(c.policy.net.activation, "relu");
  EXPECT_EQ(c.policy.net.init, "truncated_normal");
  EXPECT_DOUBLE_EQ(c.policy.net.output_scale, 0.02);
  EXPECT_DOUBLE_EQ(c.policy.log_std, -2);
  EXPECT_FALSE(c.policy.learn_std);
  EXPECT_EQ(c.policy.net.history, 4);
  EXPECT_EQ(c.value.hidden, std::vector<int>{8});
  EXPECT_DOUBLE_EQ(c.value.output_scale, 1.0);  // the value head's default gain
  EXPECT_DOUBLE_EQ(c.ppo.gamma, 0.95);
  EXPECT_EQ(c.ppo.value_epochs, 2);
  EXPECT_TRUE(c.ppo.kl_penalty);
  EXPECT_DOUBLE_EQ(c.ppo.kl_stop, 0);
  EXPECT_EQ(c.optimizer.kind, "sgd");
  EXPECT_DOUBLE_EQ(c.optimizer.policy_lr, 2.5e-6);
  EXPECT_EQ(c.optimizer.schedule, "linear");
  EXPECT_EQ(c.collect.mode, "episodes");
  EXPECT_EQ(c.collect.episodes, 10);
  EXPECT_FALSE(c.normalize.observations);
  EXPECT_TRUE(c.normalize.rewards);
  ASSERT_EQ(c.rewards.size(), 1u);
  EXPECT_DOUBLE_EQ(c.rewards[0].weight, 0.5);
}

TEST(TrainConfig, AnEncoderIsReadIntoItsNetwork) {
  const TrainConfig c = parse_train_config("policy: {encoder: {input: height_map, hidden: [30, 40]}}\n", "run.yaml");
  EXPECT_EQ(c.policy.net.encoder.input, "height_map");
  EXPECT_EQ(c.policy.net.encoder.hidden, (std::vector<int>{30, 40}));
  EXPECT_EQ(c.policy.net.encoder.offset, -1);  // resolved from the environment's layout
  EXPECT_FALSE(c.value.encoder.enabled());
  EXPECT_EQ(parse_train_config("value: {encoder: {input: height_map}}\n", "run.yaml").value.encoder.hidden, (std::vector<int>{30, 40, 100}));  // seed 002's
}

TEST(TrainConfig, ANetworkWithoutAnObservationTakesNoEncoder) {
  // A discriminator's network reads transitions, not an observation's parts: its section reads no
  // 'encoder', which is then an unknown key.
  const YamlReader r("disc.yaml");
  const YAML::Node node = r.parse("{hidden: [8], encoder: {input: height_map}}", "");
  ConfigSection s(r, node, "rewards.0.network");
  const NetworkConfig n = read_network(r, s, NetworkConfig{}, false);
  EXPECT_FALSE(n.encoder.enabled());
  try {
    s.finish();
    FAIL() << "an encoder was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("unknown key 'rewards.0.network.encoder'"), std::string::npos) << e.what();
  }
}

TEST(TrainConfig, DefaultsFollowSeed002) {
  const TrainConfig c = parse_train_config("env: {name: planar_walker}\n", "test");
  EXPECT_EQ(c.policy.net.hidden, (std::vector<int>{64, 64}));
  EXPECT_DOUBLE_EQ(c.policy.log_std, -1.0);
  EXPECT_DOUBLE_EQ(c.optimizer.policy_lr, 3e-4);
  EXPECT_DOUBLE_EQ(c.optimizer.value_lr, 1e-3);
  EXPECT_DOUBLE_EQ(c.ppo.kl_target, 0.01);
  EXPECT_DOUBLE_EQ(c.ppo.kl_stop, 4.0);
  EXPECT_EQ(c.rewards.size(), 1u);
  EXPECT_EQ(c.rewards[0].source, "env");
}

TEST(TrainConfig, ErrorsNameTheKeyAndTheLine) {
  {
    const std::string e = error_of("env: {name: planar_walker}\nppo:\n  clip: 0.2\n  epoch: 3\n");
    EXPECT_NE(e.find("run.yaml:4"), std::string::npos) << e;
    EXPECT_NE(e.find("unknown key 'ppo.epoch'"), std::string::npos) << e;
    EXPECT_NE(e.find("epochs"), std::string::npos) << e;  // the known keys are listed
  }
  {
    const std::string e = error_of("env: {name: planar_walker}\npolicy:\n  hidden: [64, big]\n");
    EXPECT_NE(e.find("run.yaml:3"), std::string::npos) << e;
    EXPECT_NE(e.find("'policy.hidden'"), std::string::npos) << e;
  }
  EXPECT_NE(error_of("ppo: {gamma: 1.5}\n").find("'ppo.gamma': 1.5 is outside [0, 1]"), std::string::npos);
  EXPECT_NE(error_of("policy: {activation: sigmoid}\n").find("'policy.activation': 'sigmoid' is not one of tanh, relu"), std::string::npos);
  EXPECT_NE(error_of("normalize: {rewards: maybe}\n").find("'normalize.rewards': expected true or false"), std::string::npos);
  EXPECT_NE(error_of("iterations: ten\n").find("'iterations': expected an integer"), std::string::npos);
  EXPECT_NE(error_of("ppo: 3\n").find("'ppo': expected a mapping"), std::string::npos);
  EXPECT_NE(error_of("collect: {envs: 8, samples: 4}\n").find("'collect.samples' (4) must be at least 'collect.envs' (8)"), std::string::npos);
  EXPECT_NE(error_of("collect: {mode: episodes}\n").find("'collect.episodes' must be >= 1"), std::string::npos);
  EXPECT_NE(error_of("seed: 1\nsead: 2\n").find("unknown key 'sead'"), std::string::npos);
  EXPECT_NE(error_of("- a\n- b\n").find("a training config is a mapping"), std::string::npos);
  EXPECT_NE(error_of("ppo: {clip: [0.2\n").find("not valid YAML"), std::string::npos);
  EXPECT_NE(error_of("rewards: [{weight: 1}]\n").find("missing 'source'"), std::string::npos);
  // An encoder names its part and reads one frame.
  EXPECT_NE(error_of("policy: {encoder: {hidden: [4]}}\n").find("'policy.encoder.input' names the observation part"), std::string::npos);
  EXPECT_NE(error_of("policy: {history: 2, encoder: {input: height_map}}\n").find("'policy.encoder' needs history 1"), std::string::npos);
}

TEST(TrainConfig, EnvironmentSectionsAreCheckedByTheFactory) {
  const YamlReader r("run.yaml");
  auto env_error = [&](const std::string& text) -> std::string {
    try {
      (void)make_env_factory(r.parse(text, "bad"), r);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(env_error("{name: walker3d}").find("'env.name': 'walker3d' is not one of"), std::string::npos);
  EXPECT_NE(env_error("{name: planar_walker, max_step: 3}").find("unknown key 'env.max_step'"), std::string::npos);
  EXPECT_NE(env_error("{max_steps: 3}").find("missing 'name'"), std::string::npos);
  EXPECT_NE(env_error("{name: reacher, links: 4}").find("'env.links': 4 is outside [2, 3]"), std::string::npos);
  EXPECT_NE(env_error("{name: imitation, character: /nonexistent/h.txt}").find("/nonexistent/h.txt not found"), std::string::npos);
  const EnvFactory f = make_env_factory(r.parse("{name: reacher, links: 3, observation: ee_to_target}", ""), r);
  const auto env = f();
  EXPECT_EQ(env->action_size(), 3);
  EXPECT_EQ(env->observation_size(), 2);
}

TEST(TrainConfig, AnnealedLogStdNeedsAFixedCovariance) {
  const TrainConfig c = parse_train_config("policy: {log_std: -1.6, learn_std: false, log_std_final: -2.3}\n", "t.yaml");
  EXPECT_DOUBLE_EQ(c.policy.log_std_final, -2.3);
  EXPECT_TRUE(std::isnan(parse_train_config("policy: {learn_std: false}\n", "t.yaml").policy.log_std_final));
  EXPECT_NE(error_of("policy: {log_std_final: -2}\n").find("set 'learn_std: false'"), std::string::npos);
  EXPECT_NE(error_of("policy: {learn_std: false, log_std_final: 9}\n").find("policy.log_std_final"), std::string::npos);
}

TEST(OverrideConfig, SetsNestedKeysAndListElementsAndNamesBadPaths) {
  const std::string text = "ppo: {clip: 0.2}\nrewards:\n  - {source: env, weight: 1}\n";
  const TrainConfig c = parse_train_config(
      override_config(text, "x.yaml", {"ppo.clip=0.1", "ppo.epochs=3", "rewards.0.weight=0.5", "collect.samples=256"}), "x.yaml");
  EXPECT_DOUBLE_EQ(c.ppo.clip, 0.1);
  EXPECT_EQ(c.ppo.epochs, 3);
  EXPECT_DOUBLE_EQ(c.rewards.at(0).weight, 0.5);
  EXPECT_EQ(c.collect.samples, 256);
  EXPECT_EQ(override_config(text, "x.yaml", {}), text);  // nothing to apply: the text as written
  auto error = [&](const std::string& setting) {
    try {
      (void)override_config(text, "x.yaml", {setting});
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error("ppo.clip").find("expected KEY.PATH=VALUE"), std::string::npos);
  EXPECT_NE(error("ppo.clip.low=1").find("'ppo.clip' is a value, not a section"), std::string::npos);
  EXPECT_NE(error("rewards.1.weight=1").find("'1' is not an index of a 1-element list"), std::string::npos);
  EXPECT_NE(error("rewards.2={source: env}").find("'2' is not an index of a 1-element list (1 appends"), std::string::npos);
  // The list's size as the last index appends an element.
  const TrainConfig two = parse_train_config(override_config(text, "x.yaml", {"rewards.1={source: env, weight: 0.25}"}), "x.yaml");
  ASSERT_EQ(two.rewards.size(), 2u);
  EXPECT_EQ(two.rewards.at(1).source, "env");
  EXPECT_DOUBLE_EQ(two.rewards.at(1).weight, 0.25);
  EXPECT_NE(error("ppo..clip=1").find("empty key"), std::string::npos);
  EXPECT_NE(error("ppo.clip=[1").find("not valid YAML"), std::string::npos);
}

// mimic train --iterations is written into the run's config.yaml: its own line replaced, comments
// and the rest of the text as they were.
TEST(WithIterations, ReplacesTheLineOrAddsOneAndKeepsComments) {
  const std::string text = "# the walk\nseed: 1\niterations: 5000   # about 20 M samples\nppo: {clip: 0.2}\n";
  EXPECT_EQ(with_iterations(text, "w.yaml", 500), "# the walk\nseed: 1\niterations: 500\nppo: {clip: 0.2}\n");
  EXPECT_EQ(parse_train_config(with_iterations(text, "w.yaml", 500), "w.yaml").iterations, 500);
  EXPECT_EQ(with_iterations(text, "w.yaml", 5000), text);  // already so: untouched
  EXPECT_EQ(with_iterations("seed: 1\n# iterations: 3 in a comment\n", "w.yaml", 7), "seed: 1\n# iterations: 3 in a comment\niterations: 7\n");
  EXPECT_EQ(with_iterations("seed: 1", "w.yaml", 7), "seed: 1\niterations: 7\n");
  EXPECT_EQ(with_iterations("iterations: 2", "w.yaml", 7), "iterations: 7\n");
  const int default_count = TrainConfig{}.iterations;  // a config without the key asks for it
  EXPECT_EQ(with_iterations("seed: 1\n", "w.yaml", default_count), "seed: 1\n");
  // A nested `iterations:` is another key; a flow-style config is re-emitted with the new count.
  EXPECT_EQ(parse_train_config(with_iterations("seed: 1\nrewards:\n  - {source: env}\n", "w.yaml", 9), "w.yaml").iterations, 9);
  EXPECT_EQ(parse_train_config(with_iterations("{seed: 1, iterations: 2}", "w.yaml", 9), "w.yaml").iterations, 9);
  EXPECT_THROW((void)with_iterations(text, "w.yaml", 0), mimic::Error);
  EXPECT_THROW((void)with_iterations("[1, 2]", "w.yaml", 3), mimic::Error);
}

TEST(ConfigDifference, NamesTheFirstKeyThatDiffersAndIgnoresCommentsLayoutThreadsAndIterations) {
  const std::string text = "seed: 1\ncollect: {envs: 4, threads: 2}\nrewards:\n  - source: iccgan\n    features: [links]\n";
  EXPECT_EQ(config_difference(text, "a.yaml", text, "b.yaml"), "");
  EXPECT_EQ(config_difference(text, "a.yaml", text + "iterations: 500\n", "b.yaml"), "");
  EXPECT_EQ(config_difference(text, "a.yaml", "# a comment\nseed: 1\ncollect:\n  envs: 4\n  threads: 1\nrewards: [{source: iccgan, features: [links]}]\n", "b.yaml"), "");
  EXPECT_EQ(config_difference(text, "a.yaml", "seed: 1\ncollect: {envs: 4}\nrewards: [{source: iccgan, features: [links, link_velocities]}]\n", "b.yaml"),
            "rewards.0.features: [links] in a.yaml, [links, link_velocities] in b.yaml");
  EXPECT_EQ(config_difference(text, "a.yaml", "seed: 2\ncollect: {envs: 4}\nrewards: [{source: iccgan, features: [links]}]\n", "b.yaml"),
            "seed: 1 in a.yaml, 2 in b.yaml");
  EXPECT_EQ(config_difference(text, "a.yaml", "collect: {envs: 4}\nrewards: [{source: iccgan, features: [links]}]\n", "b.yaml"),
            "seed: 1 in a.yaml, absent in b.yaml");
  EXPECT_EQ(config_difference(text, "a.yaml", text + "ppo: {clip: 0.1}\n", "b.yaml"), "ppo: absent in a.yaml, {clip: 0.1} in b.yaml");
  try {
    (void)config_difference("seed: [1\n", "run/config.yaml", text, "b.yaml");
    FAIL() << "bad YAML was compared";
  } catch (const mimic::Error& e) {
    EXPECT_NE(std::string(e.what()).find("run/config.yaml: not valid YAML"), std::string::npos) << e.what();
  }
}

// Every config the project ships parses, and its environment builds (those on DeepMimic's
// characters only where ../shared is present): a renamed key breaks this test, not a user's run.
TEST(ShippedConfigs, ParseAndBuildTheirEnvironments) {
  const std::filesystem::path dir = std::filesystem::path(MIMIC_SOURCE_DIR) / "configs";
  register_control_envs();  // `navigation`, as the mimic program does
  int parsed = 0, built = 0, waiting = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
    if (entry.path().extension() != ".yaml") continue;
    SCOPED_TRACE(entry.path().filename().string());
    const TrainConfig c = load_train_config(entry.path());
    ++parsed;
    const std::string name = c.env["name"].as<std::string>();
    if ((name == "imitation" || name == "tracking" || name == "navigation") && shared_data_dir().empty()) continue;
    YAML::Node env_node = YAML::Clone(c.env);
    if (name == "navigation") {
      // Its low-level skill is a run that the command in the config's header trains (from the
      // repository's root), not a shipped file: built where that run is there.
      const std::filesystem::path skill = std::filesystem::path(MIMIC_SOURCE_DIR) / env_node["skill"].as<std::string>();
      if (!std::filesystem::exists(skill / "networks.mimic")) {
        std::cout << "[ SKIPPED  ] " << entry.path().filename().string() << ": its skill " << skill.string()
                  << " is trained by the command in its header; parsed, not built\n";
        ++waiting;
        continue;
      }
      env_node["skill"] = skill.string();
    }
    const auto env = make_env_factory(env_node, YamlReader(c.source))();
    EXPECT_GT(env->observation_size(), 0);
    EXPECT_GT(env->action_size(), 0);
    ++built;
  }
  EXPECT_GE(parsed, 22);  // configs/ and the recipes of mimic imitate in configs/recipes/
  if (shared_data_dir().empty()) std::cout << "[ SKIPPED  ] ../shared/data absent: humanoid configs parsed, not built\n";
  else EXPECT_EQ(built + waiting, parsed);
}
