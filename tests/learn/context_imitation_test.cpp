// Seed 000's behaviour context in adversarial imitation: one expert file per context, the
// discriminator's one-hot or one discriminator per context (and what each learns), mismatched
// pairs, and runs started from single-behaviour runs — on the point mass's two orbits.
#include <gtest/gtest.h>

#include <iostream>

#include "core/error.hpp"
#include "core/file_io.hpp"
#include "core/statistics.hpp"
#include "env/context_env.hpp"
#include "learn/rewards/adversarial_reward.hpp"
#include "learn/rewards/per_context_reward.hpp"
#include "learn/trainer/trainer_impl.hpp"
#include "imitation_fixtures.hpp"
#include "toy_env.hpp"
#include "../error_message.hpp"
#include "../test_data.hpp"
#include "trainer_access.hpp"

using namespace mimic;
using namespace mimic::test;

TEST(AdversarialConfig, BehaviourContextsTakeOneExpertFileEach) {
  const auto dir = test::temp_dir("adversarial_contexts");
  const auto [small, large, experts] = two_orbits(dir, 2);
  const TrainOptions o = context_oscillator_options(10);
  const std::string text = "collect: {envs: 2, samples: 64}\nrewards:\n  - {source: gail, " + experts + "}\n";
  Trainer t(parse_train_config(text, "ctx.yaml"), o);
  auto* source = dynamic_cast<AdversarialRewardSource*>(impl_of(t).rewards.at(0).second.get());
  ASSERT_NE(source, nullptr);
  // Expert rows: the next state (x', v') of each file, then the file's one-hot context.
  const torch::Tensor e = source->discriminator().expert();
  ASSERT_EQ(e.size(0), 2 * small.size());
  ASSERT_EQ(e.size(1), 4);
  for (int i : {0, small.size() - 1}) {
    EXPECT_FLOAT_EQ(e[i][0].item<float>(), static_cast<float>(small.next_obs(i, 0)));
    EXPECT_FLOAT_EQ(e[i][2].item<float>(), 1.0f);
    EXPECT_FLOAT_EQ(e[i][3].item<float>(), 0.0f);
    EXPECT_FLOAT_EQ(e[small.size() + i][1].item<float>(), static_cast<float>(large.next_obs(i, 1)));
    EXPECT_FLOAT_EQ(e[small.size() + i][2].item<float>(), 0.0f);
    EXPECT_FLOAT_EQ(e[small.size() + i][3].item<float>(), 1.0f);
  }
  // The policy's rows take the context from the observation.
  Rollout r;
  r.input_size = 4, r.frame_size = 4, r.action_size = 1;
  r.raw_input = {0.5, 0.5, 1, 0};
  r.next_obs = {0.6, 0.4, 0, 1};
  r.action = {0};
  r.env_reward = {0};
  EXPECT_EQ(source->features().of(r), (FeatureRows(1, 4) << 0.6f, 0.4f, 0, 1).finished());

  auto error = [&](const std::string& cfg) {
    return error_of([&] { Trainer bad(parse_train_config(cfg, "ctx.yaml"), o); });
  };
  EXPECT_NE(error("rewards: [{source: gail, experts: [" + (dir / "small.csv").string() + "]}]")
                .find("names 1 files: the environment needs env.context with count 1"),
            std::string::npos);
  EXPECT_NE(error("rewards: [{source: gail, expert: a.csv, " + experts + "}]").find("give either 'rewards.expert'"), std::string::npos);
}

// mismatched: each context's demonstrations, seen under another context, are the policy's.
TEST(AdversarialConfig, MismatchedPairsEachFileWithTheOtherContexts) {
  const auto dir = test::temp_dir("adversarial_mismatched");
  const auto [small, large, experts] = two_orbits(dir, 2);
  const TrainOptions o = context_oscillator_options(10);
  auto source_of = [&](Trainer& t) { return impl_of(t).rewards.at(0).second.get(); };
  {  // one discriminator: the files again, each with the other one-hot
    Trainer t(parse_train_config("collect: {envs: 2, samples: 64}\nrewards:\n  - {source: gail, mismatched: 0.5, " + experts + "}\n", "ctx.yaml"), o);
    auto* source = dynamic_cast<AdversarialRewardSource*>(source_of(t));
    ASSERT_NE(source, nullptr);
    const torch::Tensor m = source->discriminator().mismatched();
    ASSERT_EQ(m.size(0), 2 * small.size());
    const int last = small.size() - 1;
    EXPECT_FLOAT_EQ(m[last][0].item<float>(), static_cast<float>(small.next_obs(last, 0)));
    EXPECT_FLOAT_EQ(m[last][2].item<float>(), 0.0f);  // the small orbit under context 1
    EXPECT_FLOAT_EQ(m[last][3].item<float>(), 1.0f);
    EXPECT_FLOAT_EQ(m[small.size()][1].item<float>(), static_cast<float>(large.next_obs(0, 1)));
    EXPECT_FLOAT_EQ(m[small.size()][2].item<float>(), 1.0f);  // the large orbit under context 0
    EXPECT_FLOAT_EQ(m[small.size()][3].item<float>(), 0.0f);
    EXPECT_EQ(source->discriminator().expert().size(0), 2 * small.size());
    // The discriminator learns to call an expert's states under the other behaviour's one-hot the
    // policy's: it catches more of the mismatched samples as it trains.
    std::vector<double> caught;
    for (int i = 0; i < 30; ++i) caught.push_back(t.iterate().get("gail_mismatched_accuracy"));
    std::cout << "[ figures  ] mismatched samples caught: " << caught.front() << " at iteration 1, " << caught.back() << " at 30\n";
    // Measured: 0.33 -> 0.55 (seeded, so these figures are fixed).
    EXPECT_GT(caught.back(), 0.5);
    EXPECT_GT(caught.back(), caught.front() + 0.15);
  }
  {  // one per context: the other file, without a one-hot
    Trainer t(parse_train_config("collect: {envs: 2, samples: 64}\nrewards:\n  - {source: gail, per_context: true, mismatched: 1, " +
                                     experts + "}\n",
                                 "ctx.yaml"),
              o);
    auto* source = dynamic_cast<PerContextRewardSource*>(source_of(t));
    ASSERT_NE(source, nullptr);
    EXPECT_TRUE(torch::equal(source->part(0).discriminator().mismatched(), source->part(1).discriminator().expert()));
    EXPECT_TRUE(torch::equal(source->part(1).discriminator().mismatched(), source->part(0).discriminator().expert()));
    const IterationMetrics it = t.iterate();
    EXPECT_FALSE(std::isnan(it.get("gail_mismatched_score_c0")));
  }
  {  // off by default
    Trainer t(parse_train_config("collect: {envs: 2, samples: 64}\nrewards:\n  - {source: gail, " + experts + "}\n", "ctx.yaml"), o);
    EXPECT_EQ(dynamic_cast<AdversarialRewardSource*>(source_of(t))->discriminator().mismatched().size(0), 0);
  }
  const std::string single = error_of([&] {
    Trainer bad(parse_train_config(gail_config(dir / "small.csv", 1, ", mismatched: 0.5"), "one.yaml"), oscillator_options());
  });
  EXPECT_NE(single.find("'rewards.mismatched' needs 'rewards.experts'"), std::string::npos) << single;
}

// Seed 000's context learnt, not only plumbed: one policy, two behaviours (the orbit of radius 1
// and the orbit of radius 2) from two expert files, the one-hot context choosing between them.
TEST(AdversarialLearning, OnePolicyLearnsTwoBehavioursFromTheContext) {
  const auto dir = test::temp_dir("gail_contexts");
  const auto [small, large, experts] = two_orbits(dir, 20);
  const int iterations = 120;
  const std::string text = with_experts(gail_config(dir / "small.csv", iterations, ", epochs: 5, lr: 3.0e-3, gradient_penalty: 1"),
                                        dir / "small.csv", experts);
  Trainer t(parse_train_config(text, "ctx.yaml"), context_oscillator_options());
  const double small_before = held_radius(t, 0), large_before = held_radius(t, 1);
  for (int i = 0; i < iterations; ++i) t.iterate();
  const double small_after = held_radius(t, 0), large_after = held_radius(t, 1);
  std::cout << "radius with context 0 (expert 1): " << small_before << " -> " << small_after << "; with context 1 (expert 2): " << large_before
            << " -> " << large_after << "\n";
  EXPECT_NEAR(small_after, 1.0, 0.3);
  EXPECT_NEAR(large_after, 2.0, 0.4);
  EXPECT_GT(large_after - small_after, 0.6);
  // The discriminator tells the contexts apart: each expert file scores higher under its own
  // context than under the other, relative to the other file (mimic score).
  auto score = [&](const Demonstrations& d, int context) { return mean_of(test::discriminator_scores(t, d, context)); };
  const double s00 = score(small, 0), s01 = score(small, 1), s10 = score(large, 0), s11 = score(large, 1);
  std::cout << "discriminator reward: small orbit " << s00 << " (context 0), " << s01 << " (context 1); large orbit " << s10
            << " (context 0), " << s11 << " (context 1)\n";
  EXPECT_GT(s00 - s01, s10 - s11 + 0.1);
  EXPECT_THROW(test::discriminator_scores(t, small, 2), Error);   // outside the run's contexts
  EXPECT_THROW(test::discriminator_scores(t, small, -1), Error);  // a context run's discriminator needs one
  Demonstrations narrow = small;
  narrow.obs = small.obs.leftCols(1);
  EXPECT_THROW(test::discriminator_scores(t, narrow, 0), Error);  // not this run's observations
}

// The same two behaviours with one discriminator per context (per_context: true): each learns
// from its context's file and samples alone, and each rates its own file above the other's.
TEST(AdversarialLearning, ADiscriminatorPerContextTeachesBothBehaviours) {
  const auto dir = test::temp_dir("gail_per_context");
  const auto [small, large, experts] = two_orbits(dir, 20);
  TrainOptions o = context_oscillator_options();
  o.run_dir = dir / "run";
  const int iterations = 120;
  const std::string text = with_experts(
      gail_config(dir / "small.csv", iterations, ", epochs: 5, lr: 3.0e-3, gradient_penalty: 1, per_context: true"), dir / "small.csv", experts);
  Trainer t(parse_train_config(text, "ctx.yaml"), o);
  ASSERT_NE(dynamic_cast<PerContextRewardSource*>(impl_of(t).rewards[0].second.get()), nullptr);
  IterationMetrics last;
  for (int i = 0; i < iterations; ++i) last = t.iterate();
  EXPECT_FALSE(std::isnan(last.get("gail_policy_accuracy_c0")));  // each part's metrics, by context
  EXPECT_FALSE(std::isnan(last.get("gail_policy_accuracy_c1")));
  const double small_after = held_radius(t, 0), large_after = held_radius(t, 1);
  auto score = [&](const Demonstrations& d, int context) { return mean_of(test::discriminator_scores(t, d, context)); };
  const double s00 = score(small, 0), s01 = score(small, 1), s10 = score(large, 0), s11 = score(large, 1);
  std::cout << "radius with context 0: " << small_after << ", with context 1: " << large_after << "; discriminator reward: small orbit "
            << s00 << " (part 0), " << s01 << " (part 1); large orbit " << s10 << " (part 0), " << s11 << " (part 1)\n";
  EXPECT_NEAR(small_after, 1.0, 0.3);  // both started near 2.37 (the test above)
  EXPECT_GT(large_after - small_after, 0.6);
  EXPECT_GT(s00, s10);  // part 0 prefers the small orbit, part 1 the large one
  EXPECT_GT(s11, s01);
  EXPECT_THROW(test::discriminator_scores(t, small, -1), Error);
  // Saved and loaded part by part.
  t.save_checkpoint(dir / "saved.pt");
  TrainOptions elsewhere = o;
  elsewhere.run_dir = dir / "again";
  Trainer again(parse_train_config(text, "ctx.yaml"), elsewhere);
  again.load_checkpoint(dir / "saved.pt");
  EXPECT_DOUBLE_EQ(mean_of(test::discriminator_scores(again, large, 1)), s11);
  EXPECT_DOUBLE_EQ(mean_of(test::discriminator_scores(again, small, 0)), s00);
  // per_context needs one file per context.
  const std::string single = error_of([&] {
    Trainer bad(parse_train_config(gail_config(dir / "small.csv", 1, ", per_context: true"), "one.yaml"), oscillator_options());
  });
  EXPECT_NE(single.find("'rewards.per_context' needs 'rewards.experts'"), std::string::npos) << single;
}

// A single-behaviour run starts a per-context run: every part begins as its discriminator.
TEST(AdversarialImitation, EveryDiscriminatorPerContextStartsAsTheSingleBehavioursOne) {
  const auto dir = test::temp_dir("gail_init_per_context");
  const auto [small, large, experts] = two_orbits(dir, 4);
  const std::string text = gail_config(dir / "small.csv", 2, ", loss: hinge, heads: 4, gradient_penalty: 1, epochs: 2");
  TrainOptions o = oscillator_options();
  o.run_dir = dir / "source";
  Trainer source(parse_train_config(text, "osc.yaml"), o);
  source.run();
  const std::string two = with_experts(text, dir / "small.csv", experts + ", per_context: true");
  TrainOptions c = context_oscillator_options();
  c.run_dir = dir / "context";
  c.init_from = dir / "source";
  Trainer t(parse_train_config(two, "osc_context.yaml"), c);
  EXPECT_EQ(t.reward_sources_initialised(), 1);
  for (const Demonstrations& d : {small, large}) {
    const std::vector<double> before = test::discriminator_scores(source, d, -1);
    for (int context : {0, 1}) {
      const std::vector<double> now = test::discriminator_scores(t, d, context);
      ASSERT_EQ(now.size(), before.size());
      for (std::size_t i = 0; i < now.size(); ++i) EXPECT_NEAR(now[i], before[i], 1e-5) << "context " << context << ", sample " << i;
    }
  }
  t.run();  // and trains on
  EXPECT_EQ(t.iteration(), 2);
}

// Each part from its own behaviour's run (--init-discriminators-from), after the policy's start:
// a context run whose policy comes from elsewhere (a distilled student) keeps both behaviours'
// trained discriminators instead of starting one of them from the other's.
TEST(AdversarialImitation, EachDiscriminatorPerContextStartsFromItsOwnBehavioursRun) {
  const auto dir = test::temp_dir("gail_init_discriminators");
  const auto [small, large, experts] = two_orbits(dir, 4);
  const std::string text = gail_config(dir / "small.csv", 2, ", loss: hinge, heads: 4, gradient_penalty: 1, epochs: 2");
  auto single = [&](const std::string& name, const std::string& expert) {
    TrainOptions o = oscillator_options();
    o.run_dir = dir / name;
    auto run = std::make_unique<Trainer>(parse_train_config(with_experts(text, dir / "small.csv", "expert: " + expert), name + ".yaml"), o);
    run->run();
    return run;
  };
  const auto small_run = single("small_run", (dir / "small.csv").string());
  const auto large_run = single("large_run", (dir / "large.csv").string());
  const std::string two = with_experts(text, dir / "small.csv", experts + ", per_context: true");
  TrainOptions c = context_oscillator_options();
  c.run_dir = dir / "context";
  c.init_from = dir / "small_run";
  c.init_discriminators_from = {dir / "small_run", dir / "large_run" / "checkpoint.pt"};
  Trainer t(parse_train_config(two, "osc_context.yaml"), c);
  EXPECT_EQ(t.reward_sources_initialised(), 1);
  EXPECT_EQ(t.context_discriminators_initialised(), 1);
  double runs_differ = 0;
  for (const Demonstrations& d : {small, large}) {
    const std::vector<double> s = test::discriminator_scores(*small_run, d, -1), l = test::discriminator_scores(*large_run, d, -1);
    const std::vector<double> part0 = test::discriminator_scores(t, d, 0), part1 = test::discriminator_scores(t, d, 1);
    ASSERT_EQ(part0.size(), s.size());
    ASSERT_EQ(part1.size(), l.size());
    for (std::size_t i = 0; i < s.size(); ++i) {
      EXPECT_NEAR(part0[i], s[i], 1e-5) << "sample " << i;
      EXPECT_NEAR(part1[i], l[i], 1e-5) << "sample " << i;
      runs_differ = std::max(runs_differ, std::abs(s[i] - l[i]));
    }
  }
  EXPECT_GT(runs_differ, 1e-3);  // else part 1 could have come from the small orbit's run
  EXPECT_NE(read_text_file(dir / "context" / "config.yaml").find("# discriminators per context started from"), std::string::npos);
  t.run();
  EXPECT_EQ(t.iteration(), 2);

  auto attempt = [&](const std::string& config, std::vector<std::filesystem::path> from, bool resume = false) {
    TrainOptions o = context_oscillator_options();
    o.run_dir = dir / (resume ? "context" : "attempt");
    o.resume = resume;
    o.init_discriminators_from = std::move(from);
    return error_of([&] { Trainer bad(parse_train_config(config, "bad.yaml"), o); });
  };
  const std::string count = attempt(two, {dir / "small_run"});
  EXPECT_NE(count.find("2 behaviour contexts, 1 runs"), std::string::npos) << count;
  const std::string no_parts = attempt(with_experts(text, dir / "small.csv", experts), {dir / "small_run", dir / "large_run"});
  EXPECT_NE(no_parts.find("no reward source with one discriminator per context"), std::string::npos) << no_parts;
  const std::string parts = attempt(two, {dir / "small_run", dir / "context"});
  EXPECT_NE(parts.find((dir / "context" / "checkpoint.pt").string() + ": its reward source 0 has one discriminator per context"),
            std::string::npos) << parts;
  TrainOptions plain = oscillator_options();
  plain.run_dir = dir / "env_reward_run";
  Trainer(parse_train_config("iterations: 1\ncollect: {envs: 2, threads: 1, samples: 64}\n", "plain.yaml"), plain).run();
  const std::string kind = attempt(two, {dir / "small_run", dir / "env_reward_run"});
  EXPECT_NE(kind.find("env_reward_run/checkpoint.pt: its reward source 0 is not of kind 'gail', which context 1's part of gail needs"),
            std::string::npos) << kind;
  // A checkpoint of a later format version is refused by its version, not by a key it lacks.
  std::filesystem::create_directories(dir / "future_run");
  torch::serialize::OutputArchive future;
  future.write("format", torch::tensor(static_cast<std::int64_t>(2)));
  future.save_to((dir / "future_run" / "checkpoint.pt").string());
  const std::string format = attempt(two, {dir / "small_run", dir / "future_run"});
  EXPECT_NE(format.find("future_run/checkpoint.pt: checkpoint format 2, this mimic reads 1"), std::string::npos) << format;
  const std::string missing = attempt(two, {dir / "small_run", dir / "nowhere"});
  EXPECT_NE(missing.find("nowhere: no such checkpoint"), std::string::npos) << missing;
  const std::string resumed = attempt(two, {dir / "small_run", dir / "large_run"}, true);
  EXPECT_NE(resumed.find("--init-discriminators-from is for a new run"), std::string::npos) << resumed;
}

TEST(AdversarialImitation, ASingleBehaviourRunStartsAContextRunWithEveryContextActingAsItDid) {
  const auto dir = test::temp_dir("gail_init_context");
  // Layouts as mimic record names them.
  const auto [small, large, experts] = two_orbits(dir, 4, {{"position", 0, 1}, {"velocity", 1, 1}});
  const std::string text = gail_config(dir / "small.csv", 2, ", loss: hinge, heads: 4, gradient_penalty: 1, replay: 1500, epochs: 2");
  TrainOptions o = oscillator_options();
  o.run_dir = dir / "source";
  Trainer source(parse_train_config(text, "osc.yaml"), o);
  source.run();
  auto& source_disc = dynamic_cast<AdversarialRewardSource&>(*impl_of(source).rewards[0].second).discriminator();

  // The same set-up over two behaviours: a one-hot after the observation, one expert file each.
  const std::string two = with_experts(text, dir / "small.csv", experts);
  TrainOptions c = context_oscillator_options();
  c.run_dir = dir / "context";
  c.init_from = dir / "source";
  Trainer t(parse_train_config(two, "osc_context.yaml"), c);
  EXPECT_EQ(t.contexts_added_by_init(), 2);
  EXPECT_EQ(t.reward_sources_initialised(), 1);
  // Every context acts as the source did (its inputs weigh zero) ...
  const Eigen::Vector2d x(0.3, -0.8);
  for (const Eigen::Vector2d& context : {Eigen::Vector2d(1, 0), Eigen::Vector2d(0, 1)}) {
    Eigen::Vector4d input;
    input << x, context;
    EXPECT_NEAR(test::act(t, input)[0], test::act(source, x)[0], 1e-6);
  }
  // (Normalised, the one-hot is ±1 and would cancel equal weights: look at them.)
  const torch::Tensor first = impl_of(t).learner->policy()->named_parameters()["net.layers.0.weight"];
  EXPECT_TRUE(torch::equal(first.slice(1, 2, 4), torch::zeros({first.size(0), 2})));
  EXPECT_TRUE(torch::equal(first.slice(1, 0, 2), impl_of(source).learner->policy()->named_parameters()["net.layers.0.weight"]));
  // ... under the source's statistics, the one-hot's those of contexts drawn evenly.
  const RunningNormalizer& norm = impl_of(t).obs_norm;
  EXPECT_DOUBLE_EQ(norm.count(), impl_of(source).obs_norm.count());
  EXPECT_TRUE(norm.mean().head(2).isApprox(impl_of(source).obs_norm.mean()));
  EXPECT_NEAR(norm.mean()[2], 0.5, 1e-12);
  EXPECT_NEAR(norm.variance()[3], 0.25, 1e-12);
  // The discriminator scores the source's expert samples as before, in either context.
  auto& disc = dynamic_cast<AdversarialRewardSource&>(*impl_of(t).rewards[0].second).discriminator();
  ASSERT_EQ(disc.input_size(), source_disc.input_size() + 2);
  const torch::Tensor expert = source_disc.expert();
  const torch::Tensor scores = source_disc.reward(expert);
  for (const torch::Tensor& one_hot : {torch::tensor({1.0f, 0.0f}), torch::tensor({0.0f, 1.0f})}) {
    const torch::Tensor with_context = torch::cat({expert, one_hot.expand({expert.size(0), 2})}, 1);
    EXPECT_TRUE(torch::allclose(disc.reward(with_context), scores, 1e-5, 1e-5));
  }
  const torch::Tensor disc_first = disc.net()->named_parameters()["layers.0.weight"];
  EXPECT_TRUE(torch::equal(disc_first.slice(1, disc.input_size() - 2), torch::zeros({disc_first.size(0), 2})));
  EXPECT_EQ(disc.replay_rows(), 0);  // the narrower replay pool is not kept
  t.run();  // and it trains on, saving a context checkpoint
  EXPECT_EQ(t.iteration(), 2);

  // One expert file for every context (features named, so the context is not among them): the
  // policy widens, the discriminator loads as it was.
  TrainOptions shared = c;
  shared.run_dir.clear();
  const std::string one_expert =
      gail_config(dir / "small.csv", 2, ", loss: hinge, heads: 4, gradient_penalty: 1, replay: 1500, epochs: 2, features: [position, velocity]");
  Trainer one(parse_train_config(one_expert, "osc_context_one_expert.yaml"), shared);
  EXPECT_EQ(one.reward_sources_initialised(), 1);
  auto& one_disc = dynamic_cast<AdversarialRewardSource&>(*impl_of(one).rewards[0].second).discriminator();
  EXPECT_TRUE(torch::allclose(one_disc.reward(expert), scores, 1e-6, 1e-6));
  // A context run cannot start one without contexts; nor can a source of another size.
  TrainOptions back = oscillator_options();
  back.init_from = dir / "context";
  const std::string env_only = text.substr(0, text.find("rewards:"));
  EXPECT_NE(error_of([&] { Trainer(parse_train_config(env_only, "osc.yaml"), back); })
                .find("context/checkpoint.pt: saved for an input of 4 and 1 actions; the config's environment has 2 and 1"),
            std::string::npos);
  TrainOptions three = c;  // three contexts: the input grew by 3, not the source's
  three.run_dir.clear();
  three.init_from = dir / "context";
  three.env_factory = [] { return std::make_unique<ContextEnv>(std::make_unique<test::OscillatorEnv>(), 3, 0); };
  EXPECT_NE(error_of([&] { Trainer(parse_train_config(env_only, "osc3.yaml"), three); })
                .find("saved for an input of 4 and 1 actions; the config's environment has 5 and 1"),
            std::string::npos);
}
