// Seed 000's behaviour context: a one-hot appended to the observation, drawn at every start and
// re-drawn every `period` steps, settable at run time, and configurable on any environment.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>

#include "core/error.hpp"
#include "core/file_io.hpp"
#include "core/yaml_reader.hpp"
#include "env/context_env.hpp"
#include "env/env_factory.hpp"
#include "env/planar_walker.hpp"
#include "test_data.hpp"

using namespace mimic;

namespace {

// The context a wrapped observation shows (exactly one 1 among the last `n` values).
int shown(const Eigen::VectorXd& obs, int n) {
  int at = -1;
  for (int j = 0; j < n; ++j) {
    const double v = obs[obs.size() - n + j];
    EXPECT_TRUE(v == 0.0 || v == 1.0);
    if (v == 1.0) {
      EXPECT_EQ(at, -1);
      at = j;
    }
  }
  return at;
}

}  // namespace

TEST(ContextEnv, AppendsTheOneHotAndRedrawsItEveryPeriod) {
  ContextEnv env(std::make_unique<PlanarWalkerEnv>(), 3, 4);
  PlanarWalkerEnv plain;
  EXPECT_EQ(env.observation_size(), plain.observation_size() + 3);
  EXPECT_EQ(env.action_size(), plain.action_size());
  EXPECT_DOUBLE_EQ(env.control_dt(), 0.008) << "the inner environment's control step (the walker's 125 Hz)";
  const auto layout = env.observation_layout();
  ASSERT_EQ(layout.back().name, "context");
  EXPECT_EQ(layout.back().offset, plain.observation_size());
  EXPECT_EQ(layout.back().size, 3);

  std::mt19937_64 rng(1), same(1);
  const Eigen::VectorXd first = env.reset(rng);
  EXPECT_TRUE(first.head(plain.observation_size()).isApprox(plain.reset(same)));  // the inner observation, untouched
  int c = shown(first, 3);
  EXPECT_EQ(c, env.context());
  std::set<int> seen{c};
  for (int t = 1; t <= 40; ++t) {
    const StepResult r = env.step(Eigen::VectorXd::Zero(env.action_size()));
    const int now = shown(r.observation, 3);
    EXPECT_EQ(now, env.context());
    if (t % 4 != 0) {
      EXPECT_EQ(now, c) << "changed between draws at step " << t;
    }
    c = now, seen.insert(now);
    if (r.done()) break;
  }
  EXPECT_GT(seen.size(), 1u);  // ten draws among three contexts

  env.set_context(2);
  EXPECT_EQ(shown(env.step(Eigen::VectorXd::Zero(env.action_size())).observation, 3), 2);
  EXPECT_THROW(env.set_context(3), Error);
  EXPECT_THROW(ContextEnv(std::make_unique<PlanarWalkerEnv>(), 1, 4), Error);
}

TEST(ContextEnv, AHeldContextOutlastsDrawsAndResetsUntilReleased) {
  ContextEnv env(std::make_unique<PlanarWalkerEnv>(), 3, 2);
  std::mt19937_64 rng(5);
  env.reset(rng);
  env.hold_context(2);
  EXPECT_TRUE(env.context_held());
  EXPECT_EQ(env.period(), 2);
  for (int episode = 0; episode < 3; ++episode) {
    EXPECT_EQ(shown(env.reset(rng), 3), 2);
    for (int t = 0; t < 12; ++t) {
      const StepResult r = env.step(Eigen::VectorXd::Zero(env.action_size()));
      EXPECT_EQ(shown(r.observation, 3), 2) << "episode " << episode << ", step " << t;
      if (r.done()) break;
    }
  }
  EXPECT_THROW(env.hold_context(-1), Error);
  env.release_context();
  EXPECT_FALSE(env.context_held());
  std::set<int> seen;
  env.reset(rng);
  for (int t = 0; t < 30; ++t) {
    const StepResult r = env.step(Eigen::VectorXd::Zero(env.action_size()));
    seen.insert(shown(r.observation, 3));
    if (r.done()) env.reset(rng);
  }
  EXPECT_GT(seen.size(), 1u);  // drawing again: 15 draws among three contexts
}

TEST(ContextEnv, ConfiguredOnAnyEnvironment) {
  const YamlReader r("ctx.yaml");
  const EnvFactory f = make_env_factory(r.parse("{name: planar_walker, context: {count: 2, period: 150}}", "bad"), r);
  const auto env = f();
  EXPECT_EQ(env->observation_layout().back().name, "context");
  EXPECT_EQ(env->observation_size(), PlanarWalkerEnv().observation_size() + 2);
  try {
    (void)make_env_factory(r.parse("{name: planar_walker, context: {count: 2, perod: 150}}", "bad"), r);
    FAIL() << "a typo in the context section must be an error";
  } catch (const ParseError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown key 'env.context.perod'"), std::string::npos) << e.what();
  }
}

TEST(EnvFactory, AModelsEnvNameIsReadFromItsConfigAndABadConfigIsNamed) {
  const auto dir = test::temp_dir("model_env_name");
  write_file_atomic(dir / "config.yaml", "seed: 1\nenv: {name: planar_walker, max_steps: 10}\n");
  EXPECT_EQ(model_env_name(dir), "planar_walker");
  const ModelEnvSection section = model_env_section(dir);
  EXPECT_EQ(section.env["max_steps"].as<int>(), 10);
  EXPECT_NE(section.reader.source().find("config.yaml"), std::string::npos) << "its messages name the file";
  EXPECT_FALSE(env_has_character(model_env_name(dir)));
  EXPECT_TRUE(env_has_character("tracking"));
  EXPECT_TRUE(env_has_character("humanoid_forward")) << "imitation's old name, in older models";
  EXPECT_FALSE(env_has_character("reacher"));
  EXPECT_FALSE(env_has_character("no_such_env"));
  EXPECT_EQ(env_names().rfind("imitation, tracking, planar_walker, reacher", 0), 0u) << env_names();
  EXPECT_EQ(env_names().find("humanoid_forward"), std::string::npos) << "the old name is accepted, not offered";
  write_file_atomic(dir / "config.yaml", "seed: 1\n");
  EXPECT_EQ(model_env_name(dir), "") << "no env section: no name";
  write_file_atomic(dir / "config.yaml", "env: {name: [\n");
  try {
    (void)model_env_name(dir);
    FAIL() << "a config that is not YAML must be an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find((dir / "config.yaml").string()), std::string::npos) << e.what();
  }
  std::filesystem::remove(dir / "config.yaml");
  EXPECT_THROW((void)model_env_name(dir), Error) << "no config.yaml";
}
