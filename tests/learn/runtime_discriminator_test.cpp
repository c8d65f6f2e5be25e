// The runtime's discriminators (control/discriminator.hpp) score transitions as the trainer's
// LibTorch reward sources do, for every kind a config can ask for: GAIL's reward forms, the
// hinge ensemble, (s), (s, s') and (s, a) features, a GRU over frames, behaviour contexts held in
// the features or one discriminator per context. And a damaged discriminator is a named error.
#include <gtest/gtest.h>

#include <iostream>

#include "control/runtime_cost.hpp"
#include "control/skill_impl.hpp"
#include "core/error.hpp"
#include "env/context_env.hpp"
#include "learn/imitation/clip_demonstrations.hpp"
#include "learn/networks/runtime_export.hpp"
#include "motion/clip_io.hpp"
#include "../error_message.hpp"
#include "../test_data.hpp"
#include "imitation_fixtures.hpp"

using namespace mimic;
using mimic::test::error_of;

namespace {

double relative_gap(const Eigen::VectorXd& ours, const std::vector<double>& reference) {
  double worst = 0;
  for (Eigen::Index i = 0; i < ours.size(); ++i) {
    const double r = reference[static_cast<std::size_t>(i)];
    worst = std::max(worst, std::abs(ours[i] - r) / std::max(1.0, std::abs(r)));
  }
  return worst;
}

// A trainer on the oscillator with `rewards` (one source), two iterations in so that the
// discriminator has learnt something, and its skill on the runtime.
struct Trained {
  std::unique_ptr<Trainer> trainer;
  std::shared_ptr<const Skill> skill;
};

Trained train(const std::string& rewards, const TrainOptions& options) {
  const std::string text =
      "seed: 3\niterations: 2\ncollect: {envs: 4, threads: 1, samples: 256}\npolicy: {hidden: [16], log_std: -0.5}\n"
      "value: {hidden: [16]}\nppo: {epochs: 1, value_epochs: 1, minibatch: 64}\nrewards:\n  - " + rewards + "\n";
  Trained t;
  t.trainer = std::make_unique<Trainer>(parse_train_config(text, "disc.yaml"), options);
  t.trainer->iterate();
  t.trainer->iterate();
  t.skill = skill_in(options.env_factory, t.trainer->runtime_networks(), "disc.mimic", "oscillator");
  return t;
}

}  // namespace

TEST(RuntimeDiscriminator, EveryKindScoresAsTheTrainersRewardSource) {
  const auto dir = test::temp_dir("runtime_discriminators");
  const Demonstrations expert = test::oscillator_expert(4);
  write_demonstrations(dir / "expert.csv", expert);
  const std::string e = "expert: " + (dir / "expert.csv").string();
  const std::vector<std::string> kinds = {
      "{source: gail, " + e + ", network: {hidden: [16, 16]}}",                                   // -log(1 - D) of s'
      "{source: gail, " + e + ", transition: ss, reward: log_d, reward_clip: 3, network: {hidden: [8]}}",
      "{source: gail, " + e + ", transition: sa, reward: logit, reward_offset: 0.5, network: {hidden: [8]}}",
      "{source: iccgan, " + e + ", heads: 4, network: {hidden: [16]}}",                          // (s, s'), mean of clipped heads
      "{source: iccgan, " + e + ", heads: 3, transition: ss, network: {history: 2, gru_size: 8, hidden: [8], activation: relu}}",
  };
  // A policy's own transitions and the expert's, including ones far outside what it learnt.
  Demonstrations d = expert;
  d.obs.bottomRows(20) *= 8.0, d.next_obs.bottomRows(20) *= 8.0, d.action.bottomRows(20) *= -8.0;
  for (const std::string& kind : kinds) {
    SCOPED_TRACE(kind);
    const Trained t = train(kind, test::oscillator_options());
    const std::vector<std::string> names = t.skill->discriminators();
    ASSERT_EQ(names.size(), 1U);
    const std::vector<double> reference = test::discriminator_scores(*t.trainer, d, -1);
    const Eigen::VectorXd ours = t.skill->score(names[0], d.obs, d.next_obs, d.action);
    ASSERT_EQ(ours.size(), static_cast<Eigen::Index>(reference.size()));
    EXPECT_LT(relative_gap(ours, reference), 1e-5);
    // The scores vary (a discriminator that gave one value everywhere would pass the line above).
    EXPECT_GT(ours.maxCoeff() - ours.minCoeff(), 1e-3);
    // Latency on the runtime times it.
    const std::vector<RuntimeCost> costs = discriminator_costs(*t.skill, 20);
    ASSERT_EQ(costs.size(), 1U);
    EXPECT_EQ(costs[0].name, names[0]);
    EXPECT_EQ(costs[0].parameters, t.skill->impl().discriminators[0].net.parameters());
  }
}

TEST(RuntimeDiscriminator, BehaviourContextsInTheFeaturesOrOneDiscriminatorEach) {
  const auto dir = test::temp_dir("runtime_discriminator_contexts");
  const test::TwoOrbits orbits = test::two_orbits(dir, 4);
  for (const std::string& per_context : {std::string("false"), std::string("true")}) {
    SCOPED_TRACE("per_context " + per_context);
    const Trained t = train("{source: gail, " + orbits.experts + ", per_context: " + per_context + ", network: {hidden: [16]}}",
                            test::context_oscillator_options());
    ASSERT_EQ(t.skill->discriminators(), std::vector<std::string>{"gail"});
    EXPECT_EQ(t.skill->impl().discriminators.size(), per_context == "true" ? 2U : 1U);
    for (const Demonstrations* d : {&orbits.small, &orbits.large})
      for (int context : {0, 1})
        EXPECT_LT(relative_gap(t.skill->score("gail", d->obs, d->next_obs, d->action, context), test::discriminator_scores(*t.trainer, *d, context)),
                  1e-5);
    EXPECT_NE(error_of([&] { (void)t.skill->score("gail", orbits.small.obs, orbits.small.next_obs, orbits.small.action); }).find("context"),
              std::string::npos);
    EXPECT_NE(error_of([&] { (void)t.skill->score("iccgan", orbits.small.obs, orbits.small.next_obs, orbits.small.action, 0); })
                  .find("no discriminator 'iccgan' (it has gail)"),
              std::string::npos);
  }
}

TEST(RuntimeDiscriminator, ADamagedDiscriminatorIsANamedError) {
  const auto dir = test::temp_dir("runtime_discriminator_damaged");
  const Demonstrations expert = test::oscillator_expert(2);
  write_demonstrations(dir / "expert.csv", expert);
  const Trained t = train("{source: iccgan, expert: " + (dir / "expert.csv").string() + ", heads: 2, network: {hidden: [8]}}",
                          test::oscillator_options());
  const std::vector<NamedArray> good = runtime_arrays(impl_of(*t.trainer));
  struct Case {
    std::string array, expected;
    std::function<void(NamedArray&)> damage;
  };
  const std::vector<Case> cases = {
      {"discriminator.0.transition", "expected s, ss or sa", [](NamedArray& a) { a = NamedArray::of_text(a.name, "sss"); }},
      {"discriminator.0.columns", "not an entry of a frame of 2 values", [](NamedArray& a) { a.f64[0] = 7; }},
      {"discriminator.0.input_std", "input_std' holds a value that is not > 0", [](NamedArray& a) { a.f32[0] = 0; }},
      {"discriminator.0.loss", "expected bce or hinge", [](NamedArray& a) { a = NamedArray::of_text(a.name, "wasserstein"); }},
      {"discriminator.0.net.layers.0.weight", "discriminator.0.net.layers.0.weight", [](NamedArray& a) { a.shape[1] += 1, a.f32.resize(a.count()); }},
      {"discriminator.count", "no array 'discriminator.1.source'", [](NamedArray& a) { a.f64[0] = 2; }},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.array);
    std::vector<NamedArray> arrays = good;
    auto it = std::find_if(arrays.begin(), arrays.end(), [&](const NamedArray& a) { return a.name == c.array; });
    ASSERT_NE(it, arrays.end());
    c.damage(*it);
    const std::string message = error_of([&] { (void)read_skill_networks(encode_arrays(arrays), "models/x/networks.mimic"); });
    EXPECT_NE(message.find("models/x/networks.mimic"), std::string::npos) << message;
    EXPECT_NE(message.find(c.expected), std::string::npos) << message;
  }
  // A file without discriminators (as written before they were added) still loads, with none.
  std::vector<NamedArray> none;
  for (const NamedArray& a : good)
    if (a.name.rfind("discriminator.", 0) != 0) none.push_back(a);
  EXPECT_TRUE(read_skill_networks(encode_arrays(none), "old.mimic")->discriminators.empty());
}

// The committed walk's discriminator, from its networks.mimic: the walk clip's transitions (as
// mimic record-clip makes them) score as expert motion and the run clip's do not (seed 004's
// switch rests on this difference).
TEST(RuntimeDiscriminator, TheCommittedWalkRatesTheWalkClipAboveTheRunClip) {
  const std::filesystem::path data = shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "needs ../shared/data (the humanoid and its clips), not found";
  const auto walk = Skill::load(std::filesystem::path(MIMIC_SOURCE_DIR) / "models" / "humanoid_walk_iccgan");
  ASSERT_EQ(walk->discriminators(), std::vector<std::string>{"iccgan"});
  const std::unique_ptr<Env> env = make_skill_env(*walk);
  CharacterEnv* character = character_of(*env);
  ASSERT_NE(character, nullptr);
  auto mean_score = [&](const std::string& clip) {
    LoadOptions load;
    const Demonstrations d = clip_demonstrations(*character, {load_motion(data / "deepmimic" / "motions" / ("humanoid3d_" + clip + ".txt"), load)}, 2);
    return walk->score("iccgan", d.obs, d.next_obs, d.action).mean();
  };
  const double walk_clip = mean_score("walk"), run_clip = mean_score("run");
  std::cout << "the walk's discriminator: walk clip " << walk_clip << ", run clip " << run_clip << " (hinge ensemble plus 1, in [0, 2])\n";
  EXPECT_GT(walk_clip - run_clip, 0.5);
}
