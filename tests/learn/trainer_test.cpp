// The trainer as a whole: checkpoints restore everything bit for bit, a run killed in the middle
// of an iteration resumes exactly where the uninterrupted run went, the same seed gives the same
// metrics with any thread count, divergence stops the run, and the walker learns.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iostream>

#include "core/error.hpp"
#include "core/file_io.hpp"
#include "learn/trainer/trainer_impl.hpp"
#include "toy_env.hpp"
#include "../humanoid_data.hpp"
#include "../test_data.hpp"
#include "trainer_access.hpp"

using namespace mimic;

namespace {

// A small walker run: 8 environments, 1024 samples per iteration.
std::string walker_config(int iterations, int threads, int checkpoint_every = 100) {
  return "seed: 3\n"
         "iterations: " + std::to_string(iterations) + "\n"
         "checkpoint_every: " + std::to_string(checkpoint_every) + "\n"
         "env: {name: planar_walker}\n"
         "collect: {envs: 8, threads: " + std::to_string(threads) + ", samples: 1024}\n"
         "policy: {hidden: [32, 32], log_std: -0.5}\n"
         "value: {hidden: [32, 32]}\n"
         "ppo: {epochs: 4, value_epochs: 4, minibatch: 128, kl_target: 0.02, kl_penalty: true}\n"
         "normalize: {rewards: true}\n";
}

TrainConfig config(const std::string& text) { return parse_train_config(text, "test.yaml"); }

// Every column but the wall-clock ones.
std::vector<std::vector<double>> deterministic_columns(const MetricsTable& t) {
  std::vector<std::vector<double>> out;
  for (std::size_t c = 0; c < t.columns.size(); ++c) {
    const std::string& n = t.columns[c];
    if (n == "wall_s" || n == "samples_per_s" || n.rfind("time_", 0) == 0) continue;
    std::vector<double> col;
    for (const auto& r : t.rows) col.push_back(r[c]);
    out.push_back(col);
  }
  return out;
}

std::vector<double> metrics_without_time(const IterationMetrics& m) {
  std::vector<double> out;
  for (const auto& [n, v] : m.values)
    if (n != "wall_s" && n != "samples_per_s" && n.rfind("time_", 0) != 0) out.push_back(v);
  return out;
}

// A run of `text` in `dir` to its end.
void run_whole(const std::string& text, const std::filesystem::path& dir) {
  TrainOptions o;
  o.run_dir = dir;
  Trainer(config(text), o).run();
}

// A run of `text` in `dir` killed (no clean-up at all) once iteration `iteration`'s collection
// has `samples` samples.
void run_killed(const std::string& text, const std::filesystem::path& dir, int iteration, int samples) {
  TrainOptions o;
  o.run_dir = dir;
  o.step_hook = [iteration, samples](int it, int n) {
    if (it == iteration && n >= samples) std::_Exit(9);
  };
  EXPECT_EXIT(Trainer(config(text), o).run(), testing::ExitedWithCode(9), "");
}

// All parameters of a module, flattened, for bitwise comparison.
std::vector<torch::Tensor> params(const torch::nn::Module& m) {
  std::vector<torch::Tensor> out;
  for (const auto& p : m.parameters()) out.push_back(p.detach().clone());
  return out;
}

void expect_identical(const std::vector<torch::Tensor>& a, const std::vector<torch::Tensor>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_TRUE(torch::equal(a[i], b[i])) << "tensor " << i;
}

// Adam's moments and step counts, in parameter order.
std::vector<torch::Tensor> adam_state(torch::optim::Optimizer& opt) {
  std::vector<torch::Tensor> out;
  for (auto& group : opt.param_groups())
    for (auto& p : group.params()) {
      auto it = opt.state().find(c10::guts::to_string(p.unsafeGetTensorImpl()));
      if (it == opt.state().end()) continue;
      auto& s = static_cast<torch::optim::AdamParamState&>(*it->second);
      out.push_back(s.exp_avg().clone());
      out.push_back(s.exp_avg_sq().clone());
      out.push_back(torch::tensor(s.step()));
    }
  return out;
}

}  // namespace

TEST(Trainer, CheckpointRoundTripIsBitIdenticalAndContinuesIdentically) {
  const auto dir = test::temp_dir("trainer_checkpoint");
  Trainer a(config(walker_config(10, 1)));
  a.iterate();
  a.iterate();
  a.save_checkpoint(dir / "c.pt");
  // Written through a temporary beside it (c.pt.tmp<pid>), renamed over it: none is left.
  for (const auto& f : std::filesystem::directory_iterator(dir)) EXPECT_EQ(f.path().filename(), "c.pt");

  Trainer b(config(walker_config(10, 1)));
  b.load_checkpoint(dir / "c.pt");
  EXPECT_EQ(b.iteration(), 2);
  EXPECT_EQ(b.samples(), a.samples());
  auto& ia = impl_of(a);
  auto& ib = impl_of(b);
  expect_identical(params(*ia.learner->policy()), params(*ib.learner->policy()));
  expect_identical(params(*ia.learner->value()), params(*ib.learner->value()));
  const auto adam_a = adam_state(ia.learner->policy_optimizer()), adam_b = adam_state(ib.learner->policy_optimizer());
  ASSERT_FALSE(adam_a.empty());
  expect_identical(adam_a, adam_b);
  expect_identical(adam_state(ia.learner->value_optimizer()), adam_state(ib.learner->value_optimizer()));
  EXPECT_EQ(ia.obs_norm.mean(), ib.obs_norm.mean());
  EXPECT_EQ(ia.obs_norm.m2(), ib.obs_norm.m2());
  EXPECT_EQ(ia.return_norm.m2(), ib.return_norm.m2());
  EXPECT_EQ(ia.learner->kl().beta(), ib.learner->kl().beta());

  // Loading restarts the episodes from the restored generators, as the saving run does after a
  // checkpoint: do that here, then both generators and both next iterations agree.
  ia.collector->reset_all();
  std::fill(ia.discounted_return.begin(), ia.discounted_return.end(), 0.0);
  EXPECT_TRUE(ia.collector->rng_states() == ib.collector->rng_states());
  EXPECT_EQ(metrics_without_time(a.iterate()), metrics_without_time(b.iterate()));
  expect_identical(params(*ia.learner->policy()), params(*ib.learner->policy()));
}

TEST(Trainer, SameSeedSameMetricsWhateverTheThreadCount) {
  Trainer a(config(walker_config(3, 1))), b(config(walker_config(3, 1))), c(config(walker_config(3, 2)));
  for (int i = 0; i < 3; ++i) {
    const auto ma = metrics_without_time(a.iterate());
    EXPECT_EQ(ma, metrics_without_time(b.iterate())) << "iteration " << i + 1;
    EXPECT_EQ(ma, metrics_without_time(c.iterate())) << "iteration " << i + 1 << " with 2 threads";
  }
  Trainer other(config("seed: 4\n" + walker_config(3, 1).substr(8)));
  EXPECT_NE(metrics_without_time(other.iterate()), metrics_without_time(Trainer(config(walker_config(3, 1))).iterate()));
}

TEST(Trainer, ResumesAfterAKillInTheMiddleOfAnIterationAsIfNeverKilled) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  const auto whole = test::temp_dir("trainer_whole"), killed = test::temp_dir("trainer_killed");
  const std::string text = walker_config(5, 2, 2);
  run_whole(text, whole);
  // Killed half-way through iteration 4: the checkpoint of iteration 2 and the CSV rows of
  // iterations 1-3 are on disk.
  run_killed(text, killed, 4, 512);
  EXPECT_EQ(read_metrics_csv(killed / "metrics.csv").rows.size(), 3u);
  TrainOptions o;
  o.run_dir = killed;
  o.resume = true;
  Trainer resumed(config(text), o);
  EXPECT_EQ(resumed.iteration(), 2);
  resumed.run();
  EXPECT_EQ(resumed.iteration(), 5);
  const MetricsTable a = read_metrics_csv(whole / "metrics.csv"), b = read_metrics_csv(killed / "metrics.csv");
  ASSERT_EQ(b.rows.size(), 5u);  // iteration 3 was redone, not written twice
  EXPECT_EQ(b.column("iteration"), (std::vector<double>{1, 2, 3, 4, 5}));
  EXPECT_EQ(deterministic_columns(a), deterministic_columns(b));
  // Two TensorBoard event files: the first segment's and the resumed one's.
  int event_files = 0;
  for (const auto& f : std::filesystem::directory_iterator(killed / "tensorboard")) event_files += f.path().filename().string().rfind("events.out.tfevents", 0) == 0;
  EXPECT_EQ(event_files, 2);
}

// collect.overlap: iteration k+1's rollout is collected with iteration k's policy while it
// learns. The first iteration is the same as without (nothing to overlap yet), the second differs
// (its rollout comes from the policy before the first update); a seed gives the same numbers every
// time; and a run killed mid-way resumes from its checkpoint exactly as the whole run went, since
// no collection runs ahead across a checkpoint.
TEST(Trainer, OverlappedCollectionLagsOneIterationRepeatsAndResumesExactly) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  const auto overlapped = [](int iterations, int checkpoint_every) {
    std::string text = walker_config(iterations, 1, checkpoint_every);
    return text.replace(text.find("samples: 1024}"), 14, "samples: 1024, overlap: true}");
  };
  {
    Trainer a(config(overlapped(4, 100))), b(config(overlapped(4, 100))), sync(config(walker_config(4, 1)));
    const auto first = metrics_without_time(a.iterate());
    EXPECT_EQ(first, metrics_without_time(b.iterate()));
    EXPECT_EQ(first, metrics_without_time(sync.iterate()));
    const auto second = metrics_without_time(a.iterate());
    EXPECT_EQ(second, metrics_without_time(b.iterate()));
    EXPECT_NE(second, metrics_without_time(sync.iterate()));
    EXPECT_EQ(metrics_without_time(a.iterate()), metrics_without_time(b.iterate()));
  }
  const auto whole = test::temp_dir("trainer_overlap_whole"), killed = test::temp_dir("trainer_overlap_killed");
  const std::string text = overlapped(7, 3);
  run_whole(text, whole);
  // Killed while iteration 5's rollout is collected beside iteration 4's learning.
  run_killed(text, killed, 5, 512);
  TrainOptions o;
  o.run_dir = killed;
  o.resume = true;
  Trainer resumed(config(text), o);
  EXPECT_EQ(resumed.iteration(), 3);
  resumed.run();
  EXPECT_EQ(deterministic_columns(read_metrics_csv(whole / "metrics.csv")), deterministic_columns(read_metrics_csv(killed / "metrics.csv")));
}

// A stop request (Ctrl-C, SIGTERM) ends the run within one collection step or one learning
// minibatch, wherever it comes, and the checkpoint holds the last completed iteration, resumable.
TEST(Trainer, AStopEndsTheRunWithinAStepOrAMinibatchAndSavesTheLastCompletedIteration) {
  const auto root = test::temp_dir("trainer_stop");
  const std::string text = walker_config(6, 1, 4);
  struct Stopped {
    RunEnd end;
    int polls_after = 0;  // polls after the request: 0 where the very next check stopped the run
  };
  // A request once iteration 3 has collected `samples`; with 1024, its whole batch, the request
  // comes one poll later, so that it falls in the PPO update.
  auto run_stopped = [&](const std::filesystem::path& dir, int samples) {
    struct State {
      bool armed = false;
      int skip = 0, after = 0;
    };
    auto state = std::make_shared<State>();
    state->skip = samples == 1024 ? 1 : 0;
    TrainOptions o;
    o.run_dir = dir;
    o.stop_requests = [state] {
      if (!state->armed) return 0;
      if (state->skip > 0) return --state->skip, 0;
      return ++state->after, 1;
    };
    o.step_hook = [state, samples](int iteration, int collected) {
      if (iteration == 3 && collected >= samples) state->armed = true;
    };
    Trainer t(config(text), o);
    Stopped s;
    s.end = t.run();
    s.polls_after = state->after;
    return s;
  };
  for (const int samples : {256, 1024}) {
    const auto dir = root / std::to_string(samples);
    const Stopped s = run_stopped(dir, samples);
    EXPECT_TRUE(s.end.stopped);
    EXPECT_EQ(s.end.iteration, 2);
    EXPECT_EQ(s.polls_after, 1) << "the first check after the request stopped the run";
    EXPECT_NE(s.end.interrupted.find(samples == 256 ? "during collection, 256 samples in" : "during the policy update of iteration 3"),
              std::string::npos)
        << s.end.interrupted;
    // Iteration 2 is not a checkpoint multiple (4): it was held in memory and written at the stop.
    Trainer check(config(text));
    check.load_checkpoint(dir / "checkpoint.pt");
    EXPECT_EQ(check.iteration(), 2);
    EXPECT_EQ(read_metrics_csv(dir / "metrics.csv").rows.size(), 2u);
    TrainOptions o;
    o.run_dir = dir;
    o.resume = true;
    Trainer resumed(config(text), o);
    EXPECT_EQ(resumed.iteration(), 2);
    EXPECT_FALSE(resumed.run().stopped);
    EXPECT_EQ(resumed.iteration(), 6);
    EXPECT_EQ(read_metrics_csv(dir / "metrics.csv").column("iteration"), (std::vector<double>{1, 2, 3, 4, 5, 6}));
  }
  // A fresh run stopped in its first iteration leaves a checkpoint of iteration 0, which resumes.
  {
    TrainOptions o;
    o.run_dir = root / "first";
    o.stop_requests = [] { return 1; };
    Trainer t(config(text), o);
    EXPECT_EQ(t.run().iteration, 0);
    Trainer check(config(text));
    check.load_checkpoint(root / "first" / "checkpoint.pt");
    EXPECT_EQ(check.iteration(), 0);
  }
}

TEST(Trainer, RefusesToOverwriteARunAndToResumeNothing) {
  const auto dir = test::temp_dir("trainer_refuse");
  TrainOptions o;
  o.run_dir = dir;
  o.resume = true;
  EXPECT_THROW(Trainer(config(walker_config(1, 1)), o), mimic::Error);
  o.resume = false;
  Trainer(config(walker_config(1, 1)), o).run();
  try {
    Trainer t(config(walker_config(1, 1)), o);
    FAIL() << "an existing run was overwritten";
  } catch (const mimic::Error& e) {
    EXPECT_NE(std::string(e.what()).find("already holds a run"), std::string::npos) << e.what();
  }
}

TEST(Trainer, ResumeRefusesAConfigOtherThanTheRunsOwn) {
  const auto dir = test::temp_dir("trainer_resume_config");
  TrainOptions o;
  o.run_dir = dir;
  Trainer(config(walker_config(1, 1)), o).run();
  o.resume = true;
  // Another clip range for the same networks would load, and silently change the run.
  std::string edited = walker_config(1, 1);
  edited.replace(edited.find("ppo: {"), 6, "ppo: {clip: 0.1, ");
  try {
    Trainer t(parse_train_config(edited, "edited.yaml"), o);
    FAIL() << "a run was resumed with another config";
  } catch (const mimic::Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("edited.yaml: differs from " + (dir / "config.yaml").string()), std::string::npos) << what;
    EXPECT_NE(what.find("(ppo.clip: absent in " + (dir / "config.yaml").string() + ", 0.1 in edited.yaml)"), std::string::npos) << what;
  }
  // The same config with other comments, another thread count and another iteration count (as
  // mimic train --iterations writes it) resumes; the run's config.yaml then records the new count,
  // and nothing else changes in it.
  const std::string same = "# the walker, on two threads\n" + walker_config(2, 2);
  Trainer t(parse_train_config(same, "same.yaml"), o);
  t.run();
  EXPECT_EQ(t.iteration(), 2);
  EXPECT_EQ(read_text_file(dir / "config.yaml"), walker_config(2, 1));
}

TEST(Trainer, AnExportedModelActsAsItsRunWithoutOptimiserStateAndIsNotResumed) {
  const auto dir = test::temp_dir("trainer_export");
  TrainOptions o;
  o.run_dir = dir / "run";
  Trainer(config(walker_config(2, 1)), o).run();
  const std::unique_ptr<Trainer> run = Trainer::from_run(dir / "run");
  ASSERT_FALSE(impl_of(*run).learner->policy_optimizer().state().empty());  // Adam has moments after two iterations
  const Eigen::VectorXd input = Eigen::VectorXd::LinSpaced(run->input_size(), -1.0, 1.0);
  const Eigen::VectorXd action = test::act(*run, input);
  std::filesystem::create_directories(dir / "model");
  write_file_atomic(dir / "model" / "config.yaml", read_text_file(dir / "run" / "config.yaml"));
  run->export_model(dir / "model" / "checkpoint.pt");
  const std::unique_ptr<Trainer> model = Trainer::from_run(dir / "model");
  EXPECT_EQ(test::act(*model, input), action);
  EXPECT_EQ(model->iteration(), 2);
  EXPECT_TRUE(impl_of(*model).learner->policy_optimizer().state().empty());
  EXPECT_TRUE(impl_of(*model).learner->value_optimizer().state().empty());
  EXPECT_LT(std::filesystem::file_size(dir / "model" / "checkpoint.pt"), std::filesystem::file_size(dir / "run" / "checkpoint.pt"));
  o.run_dir = dir / "model";
  o.resume = true;
  try {
    Trainer t(config(walker_config(2, 1)), o);
    FAIL() << "an exported model was resumed";
  } catch (const mimic::Error& e) {
    EXPECT_NE(std::string(e.what()).find("checkpoint.pt: an exported model"), std::string::npos) << e.what();
  }
}

// snapshot_every writes the policy alone at those iterations; averaging makes each weight the
// mean of the checkpoints' and reports how far their normalisers' means lie apart; a snapshot's
// policy can be taken as it was.
TEST(Trainer, SnapshotsHoldThePolicyAndAveragingTakesTheMeanOfEachWeight) {
  const auto dir = test::temp_dir("trainer_snapshots");
  TrainOptions o;
  o.run_dir = dir / "run";
  const std::string text = walker_config(4, 1) + "snapshot_every: 2\n";
  Trainer run(config(text), o);
  run.iterate();
  run.iterate();
  const std::vector<torch::Tensor> at2 = params(*impl_of(run).learner->policy());
  const RunningNormalizer norm2 = impl_of(run).obs_norm;
  run.iterate();
  run.iterate();
  run.save_checkpoint(dir / "run" / "checkpoint.pt");
  const std::vector<torch::Tensor> at4 = params(*impl_of(run).learner->policy());
  const RunningNormalizer& norm4 = impl_of(run).obs_norm;

  write_file_atomic(dir / "run" / "snapshots" / "000003 copy.pt", "a user's copy");  // not a snapshot's name: not listed
  write_file_atomic(dir / "run" / "snapshots" / "99999999999.pt", "too long for an iteration");
  const auto snapshots = Trainer::policy_snapshots(dir / "run");
  ASSERT_EQ(snapshots.size(), 2u);
  EXPECT_EQ(snapshots[0].first, 2);
  EXPECT_EQ(snapshots[1].first, 4);
  EXPECT_EQ(snapshots[0].second, Trainer::snapshot_path(dir / "run", 2));
  EXPECT_EQ(snapshots[0].second.filename(), "000002.pt");
  EXPECT_LT(std::filesystem::file_size(snapshots[1].second), std::filesystem::file_size(dir / "run" / "checkpoint.pt"));

  // A snapshot is no checkpoint: loading or starting from one says what it is.
  Trainer other(config(text));
  try {
    other.load_checkpoint(snapshots[0].second);
    FAIL() << "a snapshot loaded as a checkpoint";
  } catch (const mimic::Error& e) {
    EXPECT_NE(std::string(e.what()).find("000002.pt: a policy snapshot"), std::string::npos) << e.what();
  }

  // The run's own (iteration 4) with the snapshot at 2: the mean, weight by weight.
  Trainer averaged(config(text));
  averaged.load_checkpoint(dir / "run" / "checkpoint.pt");
  const double shift = averaged.average_policy_with({snapshots[0].second});
  const std::vector<torch::Tensor> mean = params(*impl_of(averaged).learner->policy());
  ASSERT_EQ(mean.size(), at2.size());
  bool moved = false;
  for (std::size_t i = 0; i < mean.size(); ++i) {
    EXPECT_TRUE(torch::allclose(mean[i], (at2[i] + at4[i]) / 2, 1e-6, 1e-7)) << "tensor " << i;
    moved = moved || !torch::equal(at2[i], at4[i]);
  }
  EXPECT_TRUE(moved) << "two iterations changed no weight: the test would not see averaging";
  const Eigen::ArrayXd expected_gap = (norm2.mean() - norm4.mean()).array().abs() / norm4.stddev().array().max(1e-8);
  EXPECT_NEAR(shift, expected_gap.maxCoeff(), 1e-9);
  EXPECT_GT(shift, 0.0);

  // The run as it was at iteration 2: the snapshot's policy, normaliser and counters.
  Trainer earlier(config(text));
  earlier.load_checkpoint(dir / "run" / "checkpoint.pt");
  earlier.take_policy_from(snapshots[0].second);
  expect_identical(params(*impl_of(earlier).learner->policy()), at2);
  EXPECT_EQ(impl_of(earlier).obs_norm.mean(), norm2.mean());
  EXPECT_EQ(impl_of(earlier).obs_norm.variance(), norm2.variance());
  EXPECT_EQ(earlier.iteration(), 2);
  EXPECT_EQ(earlier.samples(), 2 * 1024);

  // The snapshot at the run's own iteration holds its policy: averaging with it changes nothing.
  Trainer same(config(text));
  same.load_checkpoint(dir / "run" / "checkpoint.pt");
  EXPECT_EQ(same.average_policy_with({snapshots[1].second}), 0.0);
  expect_identical(params(*impl_of(same).learner->policy()), at4);
}

TEST(Trainer, AveragingAndTakingAPolicyRefuseAnotherNetworkOrNaNWeights) {
  const auto dir = test::temp_dir("trainer_average_mismatch");
  Trainer wide(config(walker_config(1, 1) + "snapshot_every: 1\n"));
  std::string narrow_text = walker_config(1, 1);
  narrow_text.replace(narrow_text.find("policy: {hidden: [32, 32]"), 25, "policy: {hidden: [16, 32]");
  Trainer narrow(config(narrow_text));
  narrow.save_checkpoint(dir / "narrow.pt");
  const std::vector<torch::Tensor> before = params(*impl_of(wide).learner->policy());
  try {
    wide.average_policy_with({dir / "narrow.pt"});
    FAIL() << "a policy of another shape was averaged";
  } catch (const mimic::Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("narrow.pt: its policy's '"), std::string::npos) << what;
    EXPECT_NE(what.find("not the same network"), std::string::npos) << what;
  }
  expect_identical(params(*impl_of(wide).learner->policy()), before);  // untouched on error
  EXPECT_THROW(wide.average_policy_with({dir / "absent.pt"}), mimic::Error);
  EXPECT_THROW(wide.take_policy_from(dir / "narrow.pt"), mimic::Error);
  expect_identical(params(*impl_of(wide).learner->policy()), before);

  // A policy with a NaN weight is refused by both, naming the weight; nothing changes.
  Trainer broken(config(walker_config(1, 1)));
  {
    torch::NoGradGuard no_grad;
    impl_of(broken).learner->policy()->parameters()[0].view(-1)[0] = std::nan("");
  }
  write_policy_snapshot(impl_of(broken), dir / "nan.pt");
  for (bool average : {true, false}) {
    try {
      if (average)
        wide.average_policy_with({dir / "nan.pt"});
      else
        wide.take_policy_from(dir / "nan.pt");
      FAIL() << "a NaN policy was taken";
    } catch (const mimic::Error& e) {
      EXPECT_NE(std::string(e.what()).find("nan.pt: its policy's '"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("holds NaN or infinity"), std::string::npos) << e.what();
    }
  }
  expect_identical(params(*impl_of(wide).learner->policy()), before);
}

// --init-from a run whose observation lacked a part the config now names (reference_root): the
// saved weights keep their inputs, the new part's weigh zero, so the policy acts as it did.
TEST(Trainer, ARunWithAnAddedObservationPartStartsFromOneWithoutItActingAsItDid) {
  MIMIC_NEED_HUMANOID();
  const auto dir = test::temp_dir("trainer_added_part");
  auto text = [](const std::string& observations) {
    return "seed: 3\niterations: 1\nenv: {name: tracking, max_seconds: 0.3, observations: " + observations +
           "}\ncollect: {envs: 2, samples: 64}\npolicy: {hidden: [8]}\nvalue: {hidden: [8]}\nppo: {epochs: 1, value_epochs: 1}\n";
  };
  TrainOptions o;
  o.run_dir = dir / "source";
  Trainer source(config(text("[full_state, phase]")), o);
  source.run();
  o.run_dir = dir / "widened";
  o.init_from = dir / "source";
  Trainer t(config(text("[full_state, reference_root, phase]")), o);
  EXPECT_EQ(t.parts_added_by_init(), std::vector<std::string>{"reference_root"});
  ASSERT_EQ(t.input_size(), source.input_size() + 3);
  const int state = source.input_size() - 1;  // full_state, then the phase
  Eigen::VectorXd input = Eigen::VectorXd::LinSpaced(source.input_size(), -1.0, 1.0);
  for (const Eigen::Vector3d& offset : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.4, -0.3, 2.0)}) {
    Eigen::VectorXd wide(t.input_size());
    wide << input.head(state), offset, input.tail(1);
    EXPECT_TRUE(test::act(t, wide).isApprox(test::act(source, input), 1e-6)) << offset.transpose();
  }
  // The saved statistics at their places; the new part normalised as its raw value.
  const RunningNormalizer& norm = impl_of(t).obs_norm;
  EXPECT_DOUBLE_EQ(norm.count(), impl_of(source).obs_norm.count());
  EXPECT_TRUE(norm.mean().head(state).isApprox(impl_of(source).obs_norm.mean().head(state)));
  EXPECT_DOUBLE_EQ(norm.mean()[state + 3], impl_of(source).obs_norm.mean()[state]);
  EXPECT_EQ(norm.mean().segment(state, 3), Eigen::Vector3d::Zero());
  EXPECT_TRUE(norm.variance().segment(state, 3).isApprox(Eigen::Vector3d::Ones()));
  // Parts may be added, not reordered.
  o.run_dir = dir / "reordered";
  try {
    Trainer reordered(config(text("[phase, full_state]")), o);
    FAIL() << "started a reordered observation";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("source/checkpoint.pt: observation part 'phase' of the saved network comes earlier"), std::string::npos)
        << e.what();
  }
  // Another policy history is a size mismatch that says why the inputs could not be mapped.
  o.run_dir = dir / "two_frames";
  std::string stacked = text("[full_state, phase]");
  const std::string one_frame = "policy: {hidden: [8]}\nvalue: {hidden: [8]}";
  ASSERT_NE(stacked.find(one_frame), std::string::npos);
  stacked.replace(stacked.find(one_frame), one_frame.size(), "policy: {hidden: [8], history: 2}\nvalue: {hidden: [8], history: 2}");
  try {
    Trainer two_frames(config(stacked), o);
    FAIL() << "started a two-frame policy from a one-frame one";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("saved for an input of"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("(its policy stacks another number of frames)"), std::string::npos) << e.what();
  }
}

TEST(Trainer, BadCheckpointsAreErrorsNamingTheFile) {
  const auto dir = test::temp_dir("trainer_bad_checkpoint");
  Trainer t(config(walker_config(2, 1)));
  auto message = [&](const std::filesystem::path& p) -> std::string {
    try {
      t.load_checkpoint(p);
    } catch (const mimic::Error& e) {
      return e.what();
    }
    return "";
  };
  std::ofstream(dir / "garbage.pt") << "not a checkpoint";
  EXPECT_NE(message(dir / "garbage.pt").find((dir / "garbage.pt").string() + ": not a mimic checkpoint"), std::string::npos);
  std::ofstream(dir / "empty.pt") << "";
  EXPECT_NE(message(dir / "empty.pt").find("empty file"), std::string::npos);
  t.save_checkpoint(dir / "good.pt");
  const std::string bytes = read_text_file(dir / "good.pt");
  std::ofstream(dir / "cut.pt", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  EXPECT_NE(message(dir / "cut.pt").find("cut.pt: checkpoint is truncated"), std::string::npos) << message(dir / "cut.pt");
  EXPECT_NE(message(dir / "missing.pt").find("no such checkpoint"), std::string::npos);
  torch::serialize::OutputArchive future;
  future.write("format", torch::tensor(static_cast<std::int64_t>(2)));
  future.save_to((dir / "future.pt").string());
  EXPECT_NE(message(dir / "future.pt").find("future.pt: checkpoint format 2, this mimic reads 1"), std::string::npos) << message(dir / "future.pt");
  // A checkpoint of another environment (the 3-link reacher has 3 actions, not 6).
  Trainer arm(config("env: {name: reacher, links: 3}\ncollect: {envs: 2, samples: 64}\n"));
  arm.save_checkpoint(dir / "arm.pt");
  EXPECT_NE(message(dir / "arm.pt").find("the config's environment has 17 and 6"), std::string::npos) << message(dir / "arm.pt");
}

TEST(Trainer, DivergenceStopsTheRunWithADiagnosticAndKeepsTheLastCheckpoint) {
  // The toy environment's reward turns NaN at step 5 of an episode: the collector refuses it.
  const auto dir = test::temp_dir("trainer_nan");
  TrainOptions o;
  o.run_dir = dir;
  o.env_factory = [] { return std::make_unique<test::ToyEnv>(100, 0, 5); };
  TrainConfig c = config("collect: {envs: 2, samples: 16}\ncheckpoint_every: 1\n");
  try {
    Trainer(c, o).run();
    FAIL() << "no error";
  } catch (const mimic::Error& e) {
    EXPECT_NE(std::string(e.what()).find("non-finite reward"), std::string::npos) << e.what();
  }
  // A NaN advantage reaches the loss: TrainingDiverged names the iteration and the loss.
  PpoLearner learner(2, 1, c);
  PpoBatch b;
  b.input = torch::ones({4, 2});
  b.action = torch::zeros({4, 1});
  b.old_mean = torch::zeros({4, 1});
  b.old_log_std = torch::zeros({4, 1});
  b.advantage = torch::tensor({1.f, NAN, 0.f, 2.f});
  b.target = torch::zeros({4});
  b.old_value = torch::zeros({4});
  std::mt19937_64 rng(1);
  try {
    learner.update(b, rng, false, 7);
    FAIL() << "no error";
  } catch (const TrainingDiverged& e) {
    EXPECT_NE(std::string(e.what()).find("iteration 7, epoch 1: the policy loss is NaN"), std::string::npos) << e.what();
  }
  // A run whose parameters were poisoned refuses to write a checkpoint: the last good one stays.
  TrainOptions toy;
  toy.env_factory = [] { return std::make_unique<test::ToyEnv>(3); };
  Trainer t(c, toy);
  t.iterate();
  t.save_checkpoint(dir / "last_good.pt");
  const std::string good = read_text_file(dir / "last_good.pt");
  {
    torch::NoGradGuard g;
    impl_of(t).learner->value()->parameters()[0].fill_(NAN);
  }
  EXPECT_THROW(t.save_checkpoint(dir / "last_good.pt"), TrainingDiverged);
  EXPECT_EQ(read_text_file(dir / "last_good.pt"), good);
  Trainer reload(c, toy);
  reload.load_checkpoint(dir / "last_good.pt");
  EXPECT_EQ(reload.iteration(), 1);
}

TEST(TrainerLearning, WalkerLearnsToMoveForward) {
  // Seed 002's Walker2d task, fixed seed, 16 iterations of 2048 samples (32k samples).
  const std::string text =
      "seed: 1\n"
      "iterations: 16\n"
      "env: {name: planar_walker}\n"
      "collect: {envs: 8, threads: 2, samples: 2048}\n"
      "policy: {hidden: [64, 64], log_std: -0.5}\n"
      "value: {hidden: [64, 64]}\n"
      "ppo: {epochs: 10, value_epochs: 10, minibatch: 64, kl_target: 0.02}\n";
  Trainer t(config(text));
  const double before = test::evaluate(t, 8);
  std::vector<double> returns;
  for (int i = 0; i < 16; ++i) returns.push_back(t.iterate().get("return"));
  const double after = test::evaluate(t, 8);
  const double late = (returns[13] + returns[14] + returns[15]) / 3;
  std::cout << "[ figures  ] return in iteration 1: " << returns[0] << ", iterations 14-16: " << returns[13] << ", " << returns[14] << ", "
            << returns[15] << "; mean-action return before: " << before << ", after: " << after << "\n";
  // Measured (configs/walker_ci.yaml; docs/training.md quotes these): the initial policy falls
  // within ~20 steps (return 2.6); iterations 14-16 return 269.15, 249.92, 263.35; the mean
  // action's return rises from 66 to 277. A seed gives these figures on every AVX2 machine, so
  // they are pinned: a change that moves them must say so in the docs.
  EXPECT_NEAR(returns[13], 269.154, 0.01);
  EXPECT_NEAR(returns[14], 249.923, 0.01);
  EXPECT_NEAR(returns[15], 263.349, 0.01);
  EXPECT_LT(returns[0], 20.0);
  EXPECT_GT(late, 100.0) << "returns per iteration: " << ::testing::PrintToString(returns);
  EXPECT_GT(late, 5 * returns[0]);
  EXPECT_GT(after, before + 80.0) << "deterministic return before " << before << ", after " << after;
}

TEST(Trainer, LogsWhatTheEnvironmentReportsBesidesItsRewardAsInfo) {
  // The toy environment reports its step (1, 2, 3 in 3-step episodes): 2 on the mean over 48 steps,
  // logged as info_step and kept out of the reward terms.
  TrainOptions o;
  o.env_factory = [] { return std::make_unique<test::ToyEnv>(3); };
  Trainer t(config("collect: {envs: 2, samples: 48}\n"), o);
  const IterationMetrics m = t.iterate();
  EXPECT_DOUBLE_EQ(m.get("info_step"), 2.0);
  EXPECT_TRUE(std::isnan(m.get("term_step")));
  EXPECT_FALSE(std::isnan(m.get("term_toy")));
}
