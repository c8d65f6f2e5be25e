// The torch-free runtime (control/) acts as the trainer's LibTorch networks do: on 1,000
// observations from each committed model's own episodes, and on a GRU policy, the actions agree
// within 1e-5 relative (the largest difference over max(1, the largest action)).
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <numeric>

#include "control/episodes.hpp"
#include "control/skill_impl.hpp"
#include "core/error.hpp"
#include "core/file_io.hpp"
#include "learn/imitation/imitation_eval.hpp"
#include "learn/networks/policy_timing.hpp"
#include "learn/networks/runtime_export.hpp"
#include "motion/clip_io.hpp"
#include "learn/trainer/trainer_impl.hpp"
#include "mimic/runtime.hpp"
#include "../test_data.hpp"
#include "trainer_access.hpp"

using namespace mimic;

namespace {

constexpr double kTolerance = 1e-5;
// Steps of each committed model's episodes compared. The sanitizer build runs a tenth: the same
// code on fewer steps (25 humanoids x 1,000 steps take minutes under ASan, for nothing new).
#if defined(__SANITIZE_ADDRESS__)
constexpr int kSteps = 100;
#else
constexpr int kSteps = 1000;
#endif

double relative_gap(const Eigen::MatrixXd& ours, const Eigen::MatrixXd& reference) {
  double worst = 0;
  for (Eigen::Index i = 0; i < ours.rows(); ++i)
    worst = std::max(worst, (ours.row(i) - reference.row(i)).cwiseAbs().maxCoeff() / std::max(1.0, reference.row(i).cwiseAbs().maxCoeff()));
  return worst;
}

// A model directory for the runtime from a trainer: its config and networks.mimic, and the data
// of its own that a config may name (an imitate run's clips/, start_clips/, character/).
std::filesystem::path runtime_copy(Trainer& trainer, const std::string& config_text, const std::string& name,
                                   const std::filesystem::path& model = {}) {
  const auto dir = test::temp_dir("runtime_" + name);
  write_file_atomic(dir / "config.yaml", config_text);
  trainer.write_runtime_networks(dir / kRuntimeFileName);
  for (const char* own : {"clips", "start_clips", "character", "demos.csv"})
    if (!model.empty() && std::filesystem::exists(model / own))
      std::filesystem::copy(model / own, dir / own, std::filesystem::copy_options::recursive | std::filesystem::copy_options::overwrite_existing);
  return dir;
}

std::vector<std::string> committed_models() {
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::directory_iterator(std::filesystem::path(MIMIC_SOURCE_DIR) / "models"))
    if (std::filesystem::exists(e.path() / "checkpoint.pt")) out.push_back(e.path().filename().string());
  std::sort(out.begin(), out.end());
#if defined(__SANITIZE_ADDRESS__)
  // The sanitizer build checks memory, not numerics (the release build compares every model): one
  // model of each kind of environment and network, as loading a trainer takes seconds under ASan.
  const std::vector<std::string> kinds = {"dog_trot_tracking", "humanoid_walk_iccgan", "humanoid_walk_gail", "humanoid_walk_tracking",
                                          "humanoid_walk_run_distilled_tuned", "reacher_ppo", "walker_ppo"};
  std::erase_if(out, [&](const std::string& m) { return std::find(kinds.begin(), kinds.end(), m) == kinds.end(); });
#endif
  return out;
}

class CommittedModel : public testing::TestWithParam<std::string> {};

TEST_P(CommittedModel, TorchFreeActionsMatchLibTorchsOnItsOwnEpisodes) {
  const std::filesystem::path model = std::filesystem::path(MIMIC_SOURCE_DIR) / "models" / GetParam();
  std::unique_ptr<Trainer> trainer;
  try {
    trainer = Trainer::from_run(model);
  } catch (const Error& e) {
    if (shared_data_dir().empty()) GTEST_SKIP() << GetParam() << " needs ../shared/data, not found: " << e.what();
    throw;
  }
  const auto dir = runtime_copy(*trainer, read_text_file(model / "config.yaml"), GetParam(), model);
  const auto skill = Skill::load(dir);
  ASSERT_EQ(skill->input_size(), trainer->input_size());
  // 1,000 steps of the runtime's own episodes (restarted where one ends), every input kept.
  Controller controller({skill}, 7);
  Eigen::MatrixXd inputs(kSteps, skill->input_size()), actions(kSteps, skill->action_size());
  for (int i = 0; i < kSteps; ++i) {
    const StepInfo info = controller.step();
    inputs.row(i) = controller.last_input().transpose();
    actions.row(i) = controller.last_action().transpose();
    if (info.episode_over) controller.reset();
  }
  // The controller acted one input at a time (the batch-1 kernel); the whole set as one batch
  // runs the blocked kernel.
  const Eigen::MatrixXd reference = libtorch_policy_actions(*trainer, inputs);
  const double gap = std::max(relative_gap(actions, reference), relative_gap(skill->act(inputs), reference));
  EXPECT_LT(gap, kTolerance) << GetParam();
  std::cout << "models/" << GetParam() << ": the largest relative action difference over " << kSteps << " observations is " << gap << "\n";
  // The single-input path (Trainer::act's) agrees with the batch.
  EXPECT_LT(relative_gap(skill->act(Eigen::VectorXd(inputs.row(kSteps / 2).transpose())).transpose(), test::act(*trainer, inputs.row(kSteps / 2).transpose()).transpose()),
            kTolerance);
  // A committed networks.mimic holds what the checkpoint gives (and the discriminators, which a
  // conversion without the expert files leaves out).
  if (std::filesystem::exists(model / kRuntimeFileName)) {
    const std::vector<NamedArray> committed = decode_arrays(read_text_file(model / kRuntimeFileName, kMaxCheckpointBytes));
    for (const NamedArray& a : decode_arrays(read_text_file(dir / kRuntimeFileName, kMaxCheckpointBytes))) {
      if (a.name == "discriminator.count") continue;
      const auto it = std::find_if(committed.begin(), committed.end(), [&](const NamedArray& c) { return c.name == a.name; });
      const bool same = it != committed.end() && it->shape == a.shape && it->text == a.text && it->f32 == a.f32 && it->f64 == a.f64;
      EXPECT_TRUE(same) << "models/" << GetParam() << "/networks.mimic is stale (array " << a.name << "): mimic export models/" << GetParam()
                        << " -o models/" << GetParam() << " --networks-only";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Runtime, CommittedModel, testing::ValuesIn(committed_models()),
                         [](const testing::TestParamInfo<std::string>& p) { return p.param; });

// The figures `mimic eval` prints, measured on the runtime (as eval now does) and on LibTorch
// (as it did): the same for the Table 2 skills, to well below the printed millimetre.
TEST(Runtime, TheImitationFiguresOfTheTable2SkillsAreThoseLibTorchGave) {
  const std::filesystem::path data = shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "needs ../shared/data (the humanoid and its clips), not found";
  std::vector<std::pair<std::string, std::string>> skills = {
      {"humanoid_walk_iccgan", "walk"}, {"humanoid_punch_iccgan_annealed", "punch"}, {"humanoid_kick_iccgan_total", "kick"}};
#if defined(__SANITIZE_ADDRESS__)
  skills.resize(1);  // the same code on one skill: the sanitizer build checks memory, the release build the figures
#endif
  for (const auto& [model, clip_name] : skills) {
    SCOPED_TRACE(model);
    const std::filesystem::path dir = std::filesystem::path(MIMIC_SOURCE_DIR) / "models" / model;
    const auto trainer = Trainer::from_run(dir);
    const auto skill = Skill::load(dir);
    LoadOptions load;
    const Clip clip = load_motion(data / "deepmimic" / "motions" / ("humanoid3d_" + clip_name + ".txt"), load);
    auto measure = [&](const PolicyFunction& act) {
      const std::unique_ptr<Env> env = make_skill_env(*skill);
      return measure_imitation(dynamic_cast<CharacterEnv&>(*env), act, skill->history(), 6, &clip);
    };
    const ImitationReport torch = measure([&](const Eigen::VectorXd& x) { return test::act(*trainer, x); });
    const ImitationReport ours = measure([&](const Eigen::VectorXd& x) { return skill->act(x); });
    EXPECT_NEAR(ours.error_mean(), torch.error_mean(), 1e-4);
    EXPECT_NEAR(ours.pose_error_mean(), torch.pose_error_mean(), 1e-4);
    EXPECT_EQ(ours.falls, torch.falls);
    EXPECT_EQ(ours.down, torch.down);
    std::cout << model << ": imitation error " << ours.error_mean() << " m on the runtime, " << torch.error_mean() << " on LibTorch (6 trials)\n";
  }
}

std::string walker_config(const std::string& policy) {
  return "seed: 4\niterations: 2\nenv: {name: planar_walker}\ncollect: {envs: 2, threads: 1, samples: 256}\n"
         "policy: " + policy + "\nvalue: " + policy + "\nppo: {epochs: 1, value_epochs: 1, minibatch: 64}\n";
}

// A policy of this shape on the walker, trained two iterations so that the normaliser holds
// statistics and no weight is at its initial value, then its runtime copy's actions (batches of
// 200 and of 1, which take the runtime's two kernels) and values against LibTorch's.
void expect_runtime_matches_libtorch(const std::string& network, const std::string& name, int history) {
  const std::string text = walker_config(network);
  Trainer trainer(parse_train_config(text, name + ".yaml"));
  trainer.run();
  const auto skill = Skill::load(runtime_copy(trainer, text, name));
  ASSERT_EQ(skill->history(), history);
  std::mt19937_64 rng(5);
  std::normal_distribution<double> normal(0.0, 2.0);
  Eigen::MatrixXd inputs(200, skill->input_size());
  for (Eigen::Index i = 0; i < inputs.size(); ++i) inputs.data()[i] = normal(rng);
  inputs += impl_of(trainer).obs_norm.mean().transpose().replicate(inputs.rows(), 1);
  EXPECT_LT(relative_gap(skill->act(inputs), libtorch_policy_actions(trainer, inputs)), kTolerance);
  const Eigen::MatrixXd one = inputs.topRows(1);
  EXPECT_LT(relative_gap(skill->act(one), libtorch_policy_actions(trainer, one)), kTolerance);
  torch::NoGradGuard no_grad;
  const Eigen::MatrixXf x = impl_of(trainer).obs_norm.normalize(inputs).cast<float>();
  const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rows = x;
  const torch::Tensor v = impl_of(trainer).learner->value()->forward(torch::from_blob(const_cast<float*>(rows.data()), {rows.rows(), rows.cols()}, torch::kFloat32));
  const Eigen::VectorXd value = skill->value(inputs);
  for (Eigen::Index i = 0; i < value.size(); ++i) EXPECT_NEAR(value[i], v[i].item<double>(), kTolerance * std::max(1.0, std::abs(value[i])));
}

TEST(Runtime, AGruPolicyAndItsValueActAsLibTorchsAfterTraining) {
  // A GRU over three frames (seed 004 section 5.1) with tanh layers.
  expect_runtime_matches_libtorch("{hidden: [24, 16], activation: tanh, history: 3, gru_size: 20}", "gru", 3);
}

TEST(Runtime, APolicyWithAnEncoderAndItsValueActAsLibTorchsAfterTraining) {
  // Seed 002's perceptual encoder over a middle part of the walker's observation (the root's
  // velocities, 3 of 17 inputs): the runtime must cut the same columns out, run the encoder's tanh
  // layers, and join the rest and the code in the same order as LibTorch.
  expect_runtime_matches_libtorch("{hidden: [24, 16], activation: relu, encoder: {input: root_vel, hidden: [5, 7]}}", "encoder", 1);
}

TEST(Runtime, BeforeAnyStatisticsTheNormaliserIsTheIdentity) {
  const std::string text = walker_config("{hidden: [8], activation: relu}");
  Trainer trainer(parse_train_config(text, "fresh.yaml"));
  const auto skill = Skill::load(runtime_copy(trainer, text, "fresh"));
  EXPECT_FALSE(skill->impl().normalise);
  const Eigen::MatrixXd inputs = Eigen::MatrixXd::Random(5, skill->input_size()) * 30.0;
  EXPECT_LT(relative_gap(skill->act(inputs), libtorch_policy_actions(trainer, inputs)), kTolerance);
}

}  // namespace

// `mimic eval`'s and `mimic record`'s episodes on the runtime (control/episodes.hpp) are the ones
// the trainer's collector ran for the same seed: the same starts in the same environments and the
// same exploration noise. Not bit for bit afterwards: the runtime's actions differ from LibTorch's
// by about 1e-6 (another summation order), and physics grows that over hundreds of steps, so the
// figures agree to a fraction of a percent, not to the last digit (docs/runtime.md).
TEST(Runtime, EvalAndRecordEpisodesAreTheCollectorsForTheSameSeed) {
#if defined(__SANITIZE_ADDRESS__)
  const std::vector<std::string> models = {"walker_ppo"};  // the sanitizer build checks memory on the cheaper model
#else
  const std::vector<std::string> models = {"walker_ppo", "humanoid_walk_iccgan"};
#endif
  for (const std::string& model : models) {
    const std::filesystem::path dir = std::filesystem::path(MIMIC_SOURCE_DIR) / "models" / model;
    std::unique_ptr<Trainer> trainer;
    try {
      trainer = Trainer::from_run(dir);
    } catch (const Error& e) {
      if (shared_data_dir().empty()) GTEST_SKIP() << model << " needs ../shared/data, not found: " << e.what();
      throw;
    }
    const auto skill = Skill::load(dir);
    for (const bool stochastic : {false, true}) {
      SCOPED_TRACE(model + (stochastic ? " (sampled actions)" : " (mean actions)"));
      const int episodes = model == "walker_ppo" ? 6 : 3;
      EpisodeStats torch, ours;
      std::mt19937_64 torch_noise(99), noise(99);
      const Rollout reference = impl_of(*trainer).side_episodes(episodes, 99, torch_noise, !stochastic, torch);
      EpisodeOptions o;
      o.episodes = episodes, o.slots = trainer->config().collect.envs, o.threads = 2, o.seed = 99, o.deterministic = !stochastic;
      const Rollout steps = run_episodes(*skill, o, noise, ours);
      ASSERT_EQ(steps.env_steps.size(), reference.env_steps.size());
      for (std::size_t e = 0; e < steps.env_steps.size(); ++e) {
        const int i = steps.env_steps[e].front(), j = reference.env_steps[e].front();
        // The same start, exactly, and the same noise: action - mean is sigma z for the same z.
        EXPECT_EQ(Eigen::VectorXd(steps.frame(i)), Eigen::VectorXd(reference.frame(j))) << "environment " << e;
        for (int k = 0; k < steps.action_size; ++k) {
          const std::size_t a = static_cast<std::size_t>(i * steps.action_size + k), b = static_cast<std::size_t>(j * steps.action_size + k);
          EXPECT_NEAR(steps.action[a] - steps.mean[a], reference.action[b] - reference.mean[b], 1e-5);
        }
      }
      EXPECT_EQ(ours.failures, torch.failures);
      ASSERT_EQ(ours.returns.size(), torch.returns.size());
      EXPECT_NEAR(mean_of(ours.returns), mean_of(torch.returns), 0.02 * std::abs(mean_of(torch.returns)));
      const double our_length = std::accumulate(ours.lengths.begin(), ours.lengths.end(), 0.0),
                   their_length = std::accumulate(torch.lengths.begin(), torch.lengths.end(), 0.0);
      EXPECT_NEAR(our_length, their_length, 0.01 * their_length);
      std::cout << "models/" << model << (stochastic ? " sampled" : " mean") << ": mean return " << mean_of(ours.returns) << " on the runtime, "
                << mean_of(torch.returns) << " on LibTorch; " << our_length << " and " << their_length << " steps\n";
      // record keeps every 10th step of each episode from offsets drawn after the noise.
      std::mt19937_64 offsets(5), torch_offsets(5);
      const Demonstrations recorded = demonstrations_of(steps, skill->impl().layout, 10, offsets);
      const Demonstrations kept = demonstrations_of(reference, trainer->observation_layout(), 10, torch_offsets);
      EXPECT_NEAR(recorded.size(), kept.size(), 0.01 * kept.size() + 1);
      EXPECT_EQ(recorded.episodes(), kept.episodes());
      EXPECT_LT((recorded.obs.row(0) - kept.obs.row(0)).cwiseAbs().maxCoeff(), 1e-3);  // a few steps in, the same offset
    }
  }
}

// A baseline for `mimic eval --fixed-action`: the same starts as the policy's episodes, every
// action the one given; a wrong size is an error that says both sizes.
TEST(Runtime, AFixedActionTakesThePolicysPlaceInEpisodes) {
  const auto skill = Skill::load(std::filesystem::path(MIMIC_SOURCE_DIR) / "models" / "walker_ppo");
  EpisodeOptions o;
  o.episodes = 3, o.slots = 3, o.seed = 7;
  EpisodeStats policy_stats, fixed_stats;
  std::mt19937_64 noise(1);
  const Rollout policy = run_episodes(*skill, o, noise, policy_stats);
  o.fixed_action = Eigen::VectorXd::Constant(skill->action_size(), 0.25);
  const Rollout fixed = run_episodes(*skill, o, noise, fixed_stats);
  ASSERT_EQ(fixed.env_steps.size(), 3u);
  for (std::size_t e = 0; e < 3; ++e)
    EXPECT_EQ(Eigen::VectorXd(fixed.frame(fixed.env_steps[e].front())), Eigen::VectorXd(policy.frame(policy.env_steps[e].front())));
  for (std::size_t i = 0; i < fixed.action.size(); ++i) {
    EXPECT_EQ(fixed.action[i], 0.25f);
    EXPECT_EQ(fixed.mean[i], 0.25f);
  }
  ASSERT_EQ(fixed_stats.returns.size(), 3u);
  EXPECT_LT(mean_of(fixed_stats.returns), 0.5 * mean_of(policy_stats.returns));  // the trained walker walks; a constant action does not
  o.fixed_action = Eigen::VectorXd::Zero(1);
  try {
    run_episodes(*skill, o, noise, fixed_stats);
    FAIL() << "a fixed action of the wrong size was taken";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("a fixed action of 1 finite values was given; the skill acts with " + std::to_string(skill->action_size())),
              std::string::npos)
        << e.what();
  }
}
