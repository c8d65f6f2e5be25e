// Adversarial imitation end to end: demonstrations files (round trip, malformed input), which
// numbers of a transition the discriminator sees, config errors, recording from a policy, and a
// CI-sized run in which a point mass learns to oscillate like its expert from the discriminator
// alone: the imitation error falls, the discriminator's reward rises and its accuracy drops.
// Behaviour contexts: context_imitation_test.cpp.
#include <gtest/gtest.h>

#include <fstream>
#include <iostream>

#include "core/error.hpp"
#include "core/statistics.hpp"
#include "core/file_io.hpp"
#include "env/context_env.hpp"
#include "env/imitation_env.hpp"
#include "learn/imitation/clip_demonstrations.hpp"
#include "motion/clip_io.hpp"
#include "motion/deepmimic.hpp"
#include "learn/rewards/adversarial_reward.hpp"
#include "learn/rewards/per_context_reward.hpp"
#include "learn/trainer/trainer_impl.hpp"
#include "imitation_fixtures.hpp"
#include "toy_env.hpp"
#include "../error_message.hpp"
#include "../humanoid_data.hpp"
#include "../test_data.hpp"
#include "trainer_access.hpp"

using namespace mimic;
using namespace mimic::test;

TEST(Demonstrations, RoundTripAndFirstEpisodes) {
  const auto dir = test::temp_dir("demos_round_trip");
  const Demonstrations d = oscillator_expert(3);
  write_demonstrations(dir / "d.csv", d);
  const Demonstrations back = read_demonstrations(dir / "d.csv");
  ASSERT_EQ(back.size(), 3 * test::OscillatorEnv::kLength);
  EXPECT_EQ(back.episodes(), 3);
  EXPECT_TRUE(back.obs.isApprox(d.obs, 1e-6));  // float precision on disk
  EXPECT_TRUE(back.action.isApprox(d.action, 1e-6));
  EXPECT_TRUE(back.next_obs.isApprox(d.next_obs, 1e-6));
  const Demonstrations two = back.first_episodes(2);
  EXPECT_EQ(two.size(), 2 * test::OscillatorEnv::kLength);
  EXPECT_EQ(two.episodes(), 2);
  EXPECT_EQ(two.obs.row(0), back.obs.row(0));
}

TEST(Demonstrations, AppendingKeepsEpisodesApartAndRefusesOtherColumns) {
  Demonstrations a = oscillator_expert(2), b = oscillator_expert(3);
  const Demonstrations b_copy = b;
  a.append(b);
  EXPECT_EQ(a.size(), 5 * test::OscillatorEnv::kLength);
  EXPECT_EQ(a.episodes(), 5);  // b's episodes 0..2 follow a's 0..1 as 2..4
  EXPECT_EQ(a.episode.back(), 4);
  EXPECT_EQ(a.obs.bottomRows(b.size()), b_copy.obs);
  EXPECT_EQ(a.next_obs.row(0), oscillator_expert(2).next_obs.row(0));
  Demonstrations empty;
  empty.append(b);  // into nothing: a copy
  EXPECT_EQ(empty.size(), b.size());
  Demonstrations narrow = b;
  narrow.obs.conservativeResize(Eigen::NoChange, 1);
  narrow.next_obs.conservativeResize(Eigen::NoChange, 1);
  narrow.source = "narrow.csv";
  EXPECT_NE(error_of([&] { a.append(narrow); }).find("do not match"), std::string::npos);
  Demonstrations renamed = b;
  renamed.layout = {{"speed", 0, 2}};
  renamed.source = "renamed.csv";
  EXPECT_NE(error_of([&] { a.append(renamed); }).find("renamed.csv name other observation parts"), std::string::npos);
  EXPECT_EQ(a.size(), 5 * test::OscillatorEnv::kLength);  // left as it was
}

TEST(Demonstrations, MalformedFilesNameTheFileLineAndProblem) {
  const auto dir = test::temp_dir("demos_malformed");
  write(dir / "header.csv", "iteration,obs_0\n1,2\n");
  EXPECT_NE(error_of([&] { read_demonstrations(dir / "header.csv"); }).find("header.csv:1: not a demonstrations file"), std::string::npos);
  write(dir / "sizes.csv", "episode,obs_0,obs_1,action_0,next_obs_0\n0,1,2,3,4\n");
  EXPECT_NE(error_of([&] { read_demonstrations(dir / "sizes.csv"); }).find("2 obs_, 1 action_ and 1 next_obs_"), std::string::npos);
  write(dir / "cell.csv", "episode,obs_0,action_0,next_obs_0\n0,1,2,3\n0,1,x,3\n");
  EXPECT_NE(error_of([&] { read_demonstrations(dir / "cell.csv"); }).find("cell.csv:3: 'x' is not a number"), std::string::npos);
  write(dir / "empty.csv", "episode,obs_0,action_0,next_obs_0\n0,1,,3\n");
  EXPECT_NE(error_of([&] { read_demonstrations(dir / "empty.csv"); }).find("empty.csv:2: column 'action_0'"), std::string::npos);
  write(dir / "none.csv", "episode,obs_0,action_0,next_obs_0\n");
  EXPECT_NE(error_of([&] { read_demonstrations(dir / "none.csv"); }).find("no samples"), std::string::npos);
}

TEST(TransitionFeatures, PickTheNamedSlicesOfStatesAndActions) {
  const std::vector<ObservationSlice> layout{{"a", 0, 2}, {"b", 2, 1}};
  EXPECT_EQ(slice_columns(layout, 3, {}, "x"), (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(slice_columns(layout, 3, {"b", "a"}, "x"), (std::vector<int>{2, 0, 1}));
  EXPECT_NE(error_of([&] { slice_columns(layout, 3, {"c"}, "cfg.yaml: rewards.features"); })
                .find("cfg.yaml: rewards.features: unknown observation part 'c' (this environment has: a, b)"),
            std::string::npos);

  // One sample; the policy input holds two frames, the discriminator looks at the last one.
  Rollout r;
  r.input_size = 6, r.frame_size = 3, r.action_size = 1;
  r.raw_input = {9, 9, 9, 1, 2, 3};
  r.next_obs = {4, 5, 6};
  r.action = {7};
  r.env_reward = {0};
  TransitionFeatures f;
  f.columns = {2, 0};
  f.action_size = 1;
  f.transition = "s";
  EXPECT_EQ(f.of(r), (FeatureRows(1, 2) << 6, 4).finished());
  f.transition = "ss";
  EXPECT_EQ(f.of(r), (FeatureRows(1, 4) << 3, 1, 6, 4).finished());
  f.transition = "sa";
  EXPECT_EQ(f.of(r), (FeatureRows(1, 3) << 3, 1, 7).finished());
  Demonstrations d;
  d.obs = (Eigen::MatrixXd(1, 3) << 1, 2, 3).finished();
  d.next_obs = (Eigen::MatrixXd(1, 3) << 4, 5, 6).finished();
  d.action = (Eigen::MatrixXd(1, 1) << 7).finished();
  d.episode = {0};
  EXPECT_EQ(f.of(d), f.of(r));  // the same rule for expert and policy
}

TEST(AdversarialConfig, ErrorsNameTheConfigAndTheProblem) {
  const auto dir = test::temp_dir("adversarial_config");
  write_demonstrations(dir / "expert.csv", oscillator_expert(2));
  auto build = [&](const std::string& extra) {
    return error_of([&] { Trainer t(parse_train_config(gail_config(dir / "expert.csv", 1, extra), "osc.yaml"), oscillator_options()); });
  };
  EXPECT_EQ(build(""), "");
  EXPECT_NE(build(", featurs: [position]").find("unknown key 'rewards.featurs'"), std::string::npos);
  EXPECT_NE(build(", features: [speed]").find("unknown observation part 'speed' (this environment has: position, velocity)"),
            std::string::npos);
  EXPECT_NE(build(", episodes: 5").find("2 episodes, but 'episodes' asks for 5"), std::string::npos);
  EXPECT_NE(build(", transition: sas").find("rewards.transition"), std::string::npos);
  EXPECT_NE(build(", penalty_of: mean").find("rewards.penalty_of"), std::string::npos);
  const std::string missing = error_of([&] {
    Trainer t(parse_train_config(gail_config(dir / "nowhere.csv", 1), "osc.yaml"), oscillator_options());
  });
  EXPECT_NE(missing.find("nowhere.csv' not found"), std::string::npos) << missing;
  // Demonstrations from another environment (3 observation values instead of 2).
  write(dir / "other.csv", "episode,obs_0,obs_1,obs_2,action_0,next_obs_0,next_obs_1,next_obs_2\n0,1,2,3,4,5,6,7\n");
  const std::string other = error_of([&] {
    Trainer t(parse_train_config(gail_config(dir / "other.csv", 1), "osc.yaml"), oscillator_options());
  });
  EXPECT_NE(other.find("other.csv: demonstrations have 3 observation values, the environment 2: for an expert with another body, name "
                       "the shared observation parts in 'features'"),
            std::string::npos)
      << other;
}

TEST(AdversarialConfig, TheEnsemblesDefaultsAreSeed004s) {
  const auto dir = test::temp_dir("adversarial_defaults");
  write_demonstrations(dir / "expert.csv", oscillator_expert(2));
  std::string yaml = gail_config(dir / "expert.csv", 1);
  yaml.replace(yaml.find("source: gail"), 12, "source: iccgan");
  Trainer t(parse_train_config(yaml, "osc.yaml"), oscillator_options());
  auto* source = dynamic_cast<AdversarialRewardSource*>(impl_of(t).rewards.at(0).second.get());
  ASSERT_NE(source, nullptr);
  const DiscriminatorConfig& d = source->discriminator().config();
  EXPECT_EQ(d.loss, "hinge");
  EXPECT_EQ(d.heads, 32);
  EXPECT_EQ(d.gradient_penalty, 10.0);
  EXPECT_EQ(d.penalty_of, "sum");
  EXPECT_EQ(d.standardise, "mixture");
  EXPECT_EQ(d.replay, 8192);
}

TEST(AdversarialConfig, GailsRewardFormIsChosenAndTheEnsembleRefusesIt) {
  const auto dir = test::temp_dir("adversarial_reward_form");
  write_demonstrations(dir / "expert.csv", oscillator_expert(2));
  Trainer t(parse_train_config(gail_config(dir / "expert.csv", 1, ", reward: log_d, reward_offset: 5"), "osc.yaml"), oscillator_options());
  auto* source = dynamic_cast<AdversarialRewardSource*>(impl_of(t).rewards.at(0).second.get());
  ASSERT_NE(source, nullptr);
  EXPECT_EQ(source->discriminator().config().reward, "log_d");
  // log D <= 0: with the offset of 5 every reward lies in [5 - 10, 5].
  const torch::Tensor r = source->discriminator().reward(source->discriminator().expert());
  EXPECT_LE(r.max().item<double>(), 5.0);
  EXPECT_GE(r.min().item<double>(), -5.0);
  const std::string bad = error_of([&] {
    Trainer b(parse_train_config(gail_config(dir / "expert.csv", 1, ", reward: log"), "osc.yaml"), oscillator_options());
  });
  EXPECT_NE(bad.find("reward"), std::string::npos) << bad;
  EXPECT_NE(bad.find("logit"), std::string::npos) << bad;
  std::string yaml = gail_config(dir / "expert.csv", 1, ", reward: logit");
  yaml.replace(yaml.find("source: gail"), 12, "source: iccgan");
  const std::string hinge = error_of([&] { Trainer h(parse_train_config(yaml, "osc.yaml"), oscillator_options()); });
  EXPECT_NE(hinge.find("'rewards.reward' is the bce discriminator's (GAIL)"), std::string::npos) << hinge;
}

TEST(AdversarialConfig, AnExpertWithAnotherBodyIsMatchedByItsLayout) {
  const auto dir = test::temp_dir("adversarial_other_body");
  // An expert whose observation is (pad, velocity, pad, position): its layout names the parts.
  const Demonstrations own = oscillator_expert(2);
  Demonstrations d = own;
  d.layout = {{"velocity", 1, 1}, {"position", 3, 1}};
  d.obs.resize(own.size(), 4), d.next_obs.resize(own.size(), 4);
  d.obs << Eigen::VectorXd::Constant(own.size(), 9), own.obs.col(1), Eigen::VectorXd::Constant(own.size(), 9), own.obs.col(0);
  d.next_obs << Eigen::VectorXd::Constant(own.size(), 9), own.next_obs.col(1), Eigen::VectorXd::Constant(own.size(), 9), own.next_obs.col(0);
  write_demonstrations(dir / "other_body.csv", d);
  EXPECT_EQ(read_demonstrations(dir / "other_body.csv").layout.size(), 2u);
  Trainer t(parse_train_config(gail_config(dir / "other_body.csv", 1, ", features: [position, velocity]"), "osc.yaml"), oscillator_options());
  auto* source = dynamic_cast<AdversarialRewardSource*>(impl_of(t).rewards.at(0).second.get());
  ASSERT_NE(source, nullptr);
  // The expert features are position then velocity, taken from columns 3 and 1 of the other
  // body's observation: the same numbers this environment's own expert gives.
  const FeatureRows mine = source->features().of(own);
  const torch::Tensor x = torch::from_blob(const_cast<float*>(mine.data()), {mine.rows(), mine.cols()}, torch::kFloat32);
  EXPECT_TRUE(torch::allclose(source->discriminator().expert(), x, 1e-6, 1e-6));
  std::ofstream(dir / "bad_layout.csv") << "# layout: position 3 2\nepisode,obs_0,action_0,next_obs_0\n0,1,2,3\n";
  EXPECT_NE(error_of([&] { read_demonstrations(dir / "bad_layout.csv"); }).find("bad_layout.csv:1: layout part 'position' (2 values from 3) lies outside"),
            std::string::npos);
}

TEST(Record, KeepsEveryNthStepOfEachEpisodeFromThePolicy) {
  const auto dir = test::temp_dir("record");
  write_demonstrations(dir / "expert.csv", oscillator_expert(2));
  Trainer t(parse_train_config(gail_config(dir / "expert.csv", 1), "osc.yaml"), oscillator_options());
  std::vector<double> returns;
  const Demonstrations d = test::record(t, 5, 10, /*deterministic=*/false, 3, &returns);
  EXPECT_EQ(returns.size(), 5u);
  EXPECT_EQ(d.episodes(), 5);
  EXPECT_EQ(d.size(), 5 * test::OscillatorEnv::kLength / 10);
  // Transitions are consistent with the environment: x' = x + v' dt.
  for (int i = 0; i < d.size(); ++i)
    EXPECT_NEAR(d.next_obs(i, 0), d.obs(i, 0) + d.next_obs(i, 1) * test::OscillatorEnv::kDt, 1e-9);
}

namespace {

// A run's metrics over `iterations` iterations, and the mean of one over iterations [from, to).
struct LearningCurve {
  std::vector<IterationMetrics> m;
  LearningCurve(Trainer& t, int iterations) {
    for (int i = 0; i < iterations; ++i) m.push_back(t.iterate());
  }
  double mean(const char* name, int from, int to) const {
    double s = 0;
    for (int i = from; i < to; ++i) s += m[static_cast<std::size_t>(i)].get(name);
    return s / (to - from);
  }
};

}  // namespace

TEST(AdversarialLearning, PointMassLearnsToOscillateFromTheDiscriminatorAlone) {
  const auto dir = test::temp_dir("gail_oscillator");
  write_demonstrations(dir / "expert.csv", oscillator_expert(20));
  // A quick discriminator and a slow policy, so that the discriminator leads early on and the
  // adversarial game is visible: it catches the policy's samples, then less as the policy imitates.
  const int iterations = 60;
  Trainer t(parse_train_config(gail_config(dir / "expert.csv", iterations, ", epochs: 5, lr: 3.0e-3, gradient_penalty: 1") +
                                   "optimizer: {policy_lr: 5.0e-5}\n",
                               "osc.yaml"),
            oscillator_options());
  const LearningCurve curve(t, iterations);
  auto mean = [&](const char* name, int from, int to) { return curve.mean(name, from, to); };
  // The task reward the policy never sees: minus the squared distance of (x, v) from the circle.
  const double error_early = -mean("return", 0, 3), error_late = -mean("return", iterations - 15, iterations);
  // Iterations 5-10: the discriminator has learnt; the policy has barely moved.
  const double caught_early = mean("gail_policy_accuracy", 4, 10), caught_late = mean("gail_policy_accuracy", iterations - 15, iterations);
  const double reward_early = mean("gail_reward", 4, 10), reward_late = mean("gail_reward", iterations - 15, iterations);
  std::cout << "imitation error (sum over an episode of (radius - 1)^2) " << error_early << " -> " << error_late
            << "; policy samples the discriminator catches " << caught_early << " -> " << caught_late << "; gail reward " << reward_early
            << " -> " << reward_late << "\n";
  EXPECT_LT(error_late, 0.1 * error_early);
  EXPECT_LT(caught_late, caught_early - 0.1);
  EXPECT_GT(reward_late, reward_early + 0.05);
}

// Seed 004's ensemble (hinge heads over shared layers, a gradient penalty on interpolates, reward
// the mean of the clipped heads), the humanoid's method, learnt end to end on the point mass: the
// policy, which never sees the task, comes to hold the expert's orbit from the ensemble alone.
TEST(AdversarialLearning, PointMassLearnsToOscillateFromTheEnsembleAlone) {
  const auto dir = test::temp_dir("ensemble_oscillator");
  write_demonstrations(dir / "expert.csv", oscillator_expert(20));
  const int iterations = 60;
  std::string text = gail_config(dir / "expert.csv", iterations, ", heads: 8, epochs: 5, lr: 3.0e-3, batch: 128, replay: 4096") +
                     "optimizer: {policy_lr: 5.0e-5}\n";
  text.replace(text.find("source: gail"), 12, "source: iccgan");
  Trainer t(parse_train_config(text, "osc.yaml"), oscillator_options());
  const LearningCurve curve(t, iterations);
  auto mean = [&](const char* name, int from, int to) { return curve.mean(name, from, to); };
  const double error_early = -mean("return", 0, 3), error_late = -mean("return", iterations - 15, iterations);
  const double reward_early = mean("iccgan_reward", 4, 10), reward_late = mean("iccgan_reward", iterations - 15, iterations);
  std::cout << "[ figures  ] imitation error " << error_early << " -> " << error_late << "; ensemble reward " << reward_early << " -> "
            << reward_late << "; heads' penalty at the end " << mean("iccgan_penalty", iterations - 15, iterations) << "\n";
  EXPECT_LT(error_late, 0.1 * error_early);
  EXPECT_GT(reward_late, reward_early + 0.05);
}

TEST(ClipDemonstrations, ObserveTheClipEveryControlStepWithoutActions) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  const auto walk = test::humanoid3d_motion(ch, "humanoid3d_walk.txt");
  ImitationEnvConfig cfg;
  cfg.init_noise = 0.0;
  auto env = make_imitation_env(ch, walk, cfg);
  const Demonstrations d = clip_demonstrations(*env, *walk, 2);
  const int per_pass = static_cast<int>(std::floor(walk->duration() * 30.0));  // 30 Hz control
  EXPECT_NEAR(d.size(), 2 * per_pass, 2);
  EXPECT_EQ(d.episodes(), 2);
  EXPECT_EQ(d.action.cols(), 0);
  EXPECT_EQ(d.obs.cols(), env->observation_size());
  EXPECT_EQ(d.layout.size(), env->observation_layout().size());
  // Within a pass, each transition starts where the previous one ended.
  for (int i = 0; i + 1 < per_pass - 1; ++i) EXPECT_TRUE(d.next_obs.row(i).isApprox(d.obs.row(i + 1), 1e-9)) << i;
  // The observation follows the clip: consecutive states differ.
  EXPECT_GT((d.next_obs.row(0) - d.obs.row(0)).norm(), 1e-3);
  // A round trip through a file keeps the 0 action columns.
  const auto tmp = test::temp_dir("clip_demos");
  write_demonstrations(tmp / "walk.csv", d);
  EXPECT_EQ(read_demonstrations(tmp / "walk.csv").action.cols(), 0);
  // Several clips in one set: each clip's passes, as episodes of their own.
  const auto run = test::humanoid3d_motion(ch, "humanoid3d_run.txt");
  const Demonstrations both = clip_demonstrations(*env, std::vector<Clip>{*walk, *run}, 2);
  const Demonstrations run_only = clip_demonstrations(*env, *run, 2);
  EXPECT_EQ(both.size(), d.size() + run_only.size());
  EXPECT_EQ(both.episodes(), 4);
  EXPECT_TRUE(both.obs.bottomRows(run_only.size()).isApprox(run_only.obs, 1e-12));
  // A clip of another body is refused.
  std::filesystem::path dog_dir;
  MIMIC_REQUIRE_SHARED("deepmimic/characters/dog3d.txt", dog_dir);
  const Clip dog = load_motion(test::shared_data() / "deepmimic/motions/dog3d_trot.txt", LoadOptions{});
  EXPECT_NE(error_of([&] { clip_demonstrations(*env, dog); }).find("does not fit the environment's character"), std::string::npos);
}

TEST(ClipDemonstrations, ALinkHistoryHoldsTheClipsPreviousPoses) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  const auto walk = test::humanoid3d_motion(ch, "humanoid3d_walk.txt");
  ImitationEnvConfig cfg;
  cfg.env.observations = ObservationConfig{.names = {"links"}, .link_history = 3};
  auto env = make_imitation_env(ch, walk, cfg);
  const Demonstrations d = clip_demonstrations(*env, *walk);
  const int nj = ch.skeleton.num_joints();
  const double dt = 1.0 / 30;
  // Row i is the clip at i dt: its oldest frame is the root at (i - 2) dt in the heading frame at
  // i dt (seed 004's o_{t-3:t+1} for the expert, as the policy's own history in mid-episode).
  for (const int i : {0, 1, 5, 20}) {
    const double t = i * dt;
    const Vec3 expected = HeadingFrame::of(walk->sample(t)).to_local(walk->sample(t - 2 * dt).root_pos);
    EXPECT_LT((Vec3(d.obs.row(i).segment(0, 3).transpose()) - expected).norm(), 1e-6) << i;
    const Vec3 middle = HeadingFrame::of(walk->sample(t + dt)).to_local(walk->sample(t).root_pos);
    EXPECT_LT((Vec3(d.next_obs.row(i).segment(7 * nj, 3).transpose()) - middle).norm(), 1e-6) << i;
  }
}

TEST(AdversarialImitation, AnExportedModelKeepsTheDiscriminatorsScoresAndDropsItsReplay) {
  const auto dir = test::temp_dir("gail_export");
  write_demonstrations(dir / "expert.csv", oscillator_expert(4));
  const TrainConfig cfg = parse_train_config(
      gail_config(dir / "expert.csv", 2, ", loss: hinge, heads: 4, gradient_penalty: 1, replay: 1500, epochs: 2"), "osc.yaml");
  Trainer t(cfg, oscillator_options());
  t.run();
  auto& disc = dynamic_cast<AdversarialRewardSource&>(*impl_of(t).rewards[0].second).discriminator();
  ASSERT_EQ(disc.replay_rows(), 1500);
  const torch::Tensor scores = disc.reward(disc.expert());
  t.save_checkpoint(dir / "run.pt");
  t.export_model(dir / "model.pt");
  Trainer model(cfg, oscillator_options());
  model.load_checkpoint(dir / "model.pt");
  auto& loaded = dynamic_cast<AdversarialRewardSource&>(*impl_of(model).rewards[0].second).discriminator();
  EXPECT_TRUE(torch::equal(loaded.reward(loaded.expert()), scores));
  EXPECT_EQ(loaded.replay_rows(), 0);
  EXPECT_LT(std::filesystem::file_size(dir / "model.pt"), std::filesystem::file_size(dir / "run.pt"));
  // Resuming the model is refused as an exported model even where its expert file did not travel
  // with it (the refusal comes before the discriminator loads its demonstrations).
  std::filesystem::create_directories(dir / "model");
  std::filesystem::rename(dir / "model.pt", dir / "model" / "checkpoint.pt");
  write_file_atomic(dir / "model" / "config.yaml", cfg.text);
  std::filesystem::remove(dir / "expert.csv");
  TrainOptions o = oscillator_options();
  o.run_dir = dir / "model";
  o.resume = true;
  try {
    Trainer resumed(cfg, o);
    FAIL() << "an exported model was resumed";
  } catch (const mimic::Error& e) {
    EXPECT_NE(std::string(e.what()).find("checkpoint.pt: an exported model"), std::string::npos) << e.what();
  }
}

TEST(AdversarialImitation, ACheckpointedRunResumesExactlyWithItsDiscriminator) {
  const auto dir = test::temp_dir("gail_resume");
  write_demonstrations(dir / "expert.csv", oscillator_expert(4));
  // The ensemble with every piece of state: replay buffer, gradient penalty draws, Adam moments.
  const std::string text = gail_config(dir / "expert.csv", 4, ", loss: hinge, heads: 4, gradient_penalty: 1, replay: 1500, epochs: 2");
  auto without_time = [](const IterationMetrics& m) {
    std::vector<double> out;
    for (const auto& [n, v] : m.values)
      if (n != "wall_s" && n != "samples_per_s" && n.rfind("time_", 0) != 0) out.push_back(v);
    return out;
  };
  std::vector<std::vector<double>> straight, resumed;
  {
    TrainOptions o = oscillator_options();
    o.run_dir = dir / "straight";
    Trainer t(parse_train_config(text + "checkpoint_every: 2\n", "osc.yaml"), o);
    for (int i = 0; i < 4; ++i) straight.push_back(without_time(t.iterate()));
  }
  {
    TrainOptions o = oscillator_options();
    o.run_dir = dir / "halves";
    Trainer t(parse_train_config(text + "checkpoint_every: 2\n", "osc.yaml"), o);
    for (int i = 0; i < 2; ++i) resumed.push_back(without_time(t.iterate()));
  }
  TrainOptions o = oscillator_options();
  o.run_dir = dir / "halves";
  o.resume = true;
  Trainer t(parse_train_config(text + "checkpoint_every: 2\n", "osc.yaml"), o);
  ASSERT_EQ(t.iteration(), 2);
  for (int i = 0; i < 2; ++i) resumed.push_back(without_time(t.iterate()));
  EXPECT_EQ(resumed, straight);
}

// mimic train --init-from: a new run under a changed config (here a fixed action noise and
// another learning rate) starts from another run's policy, value, normalisers and discriminator,
// with fresh optimisers and counters.
TEST(AdversarialImitation, ANewRunStartsFromAnotherRunsWeightsUnderAChangedConfig) {
  const auto dir = test::temp_dir("gail_init_from");
  write_demonstrations(dir / "expert.csv", oscillator_expert(4));
  const std::string text = gail_config(dir / "expert.csv", 2, ", loss: hinge, heads: 4, gradient_penalty: 1, replay: 1500, epochs: 2");
  TrainOptions o = oscillator_options();
  o.run_dir = dir / "source";
  Trainer source(parse_train_config(text, "osc.yaml"), o);
  source.run();
  const Eigen::VectorXd input = Eigen::Vector2d(0.3, -0.8);
  auto& source_disc = dynamic_cast<AdversarialRewardSource&>(*impl_of(source).rewards[0].second).discriminator();
  const torch::Tensor scores = source_disc.reward(source_disc.expert());

  std::string changed = text;
  changed.replace(changed.find("log_std: -0.5}"), 14, "log_std: -2.0, learn_std: false}");
  changed += "optimizer: {policy_lr: 1.0e-5}\n";
  TrainOptions fine = oscillator_options();
  fine.run_dir = dir / "fine";
  fine.init_from = dir / "source";
  Trainer t(parse_train_config(changed, "osc_fixed_noise.yaml"), fine);
  EXPECT_EQ(t.iteration(), 0);
  EXPECT_EQ(t.samples(), 0);
  EXPECT_EQ(t.reward_sources_initialised(), 1);
  EXPECT_EQ(test::act(t, input), test::act(source, input));  // the same mean action: policy and normaliser
  EXPECT_TRUE(torch::allclose(impl_of(t).learner->policy()->log_std(), torch::full({1}, -2.0)));  // the config's fixed noise
  EXPECT_TRUE(impl_of(t).learner->policy_optimizer().state().empty());
  auto& disc = dynamic_cast<AdversarialRewardSource&>(*impl_of(t).rewards[0].second).discriminator();
  EXPECT_TRUE(torch::equal(disc.reward(disc.expert()), scores));
  t.iterate();  // and it trains on
  EXPECT_EQ(t.iteration(), 1);

  // A config whose rewards are the env's alone takes the networks, not the discriminator.
  TrainOptions plain = oscillator_options();
  plain.init_from = dir / "source" / "checkpoint.pt";
  std::string env_only = text.substr(0, text.find("rewards:"));
  EXPECT_EQ(Trainer(parse_train_config(env_only, "osc_env.yaml"), plain).reward_sources_initialised(), 0);
  // Another input size, a missing checkpoint, and resume with it are errors naming the file.
  plain.init_from = dir / "nowhere";
  EXPECT_NE(error_of([&] { Trainer(parse_train_config(env_only, "osc_env.yaml"), plain); }).find("nowhere: no such checkpoint"), std::string::npos);
  plain.init_from = dir / "source";
  plain.run_dir = dir / "source";
  plain.resume = true;
  EXPECT_NE(error_of([&] { Trainer(parse_train_config(text, "osc.yaml"), plain); }).find("--init-from is for a new run"), std::string::npos);
}
