// The imitation error of DESIGN.md section 5 (seed 004 eq. 7): pinned on synthetic trajectories
// with known offsets, then measured on the humanoid for a policy that follows the clip and one
// that stands still.
#include "learn/imitation/imitation_eval.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "env/imitation_env.hpp"
#include "env/tracking.hpp"
#include "../humanoid_data.hpp"

using namespace mimic;

namespace {

LinkFrames links(std::vector<Vec3> positions) {
  LinkFrames f;
  f.joint_pos = std::move(positions);
  f.joint_rot.assign(f.joint_pos.size(), Quat::Identity());
  return f;
}

}  // namespace

TEST(ImitationError, MeanOverLinksOfTheDistance) {
  const LinkFrames ref = links({Vec3(0, 0, 1), Vec3(1, 0, 1)});
  // Every link 0.5 m off (a 3-4-5 triangle): 0.5.
  EXPECT_NEAR(link_position_error(links({Vec3(0.3, 0.4, 1), Vec3(1.3, 0.4, 1)}), ref), 0.5, 1e-12);
  // One link 0.5 m off, the other exact: 0.25.
  EXPECT_NEAR(link_position_error(links({Vec3(0, 0, 1.5), Vec3(1, 0, 1)}), ref), 0.25, 1e-12);
  EXPECT_THROW(link_position_error(links({Vec3::Zero()}), ref), Error);
}

TEST(ImitationError, AveragedOverATrajectoryWithAKnownOffset) {
  // A reference moving along x; the copy lags 0.2 m for the first half and is exact after.
  std::vector<LinkFrames> ref, sim;
  for (int f = 0; f < 10; ++f) {
    const Vec3 p(0.1 * f, 0, 1), q(0.1 * f, 0.3, 1);
    ref.push_back(links({p, q}));
    const Vec3 lag = f < 5 ? Vec3(-0.2, 0, 0) : Vec3::Zero();
    sim.push_back(links({p + lag, q + lag}));
  }
  EXPECT_NEAR(trajectory_error(sim, ref), 0.1, 1e-12);
  EXPECT_NEAR(trajectory_error(ref, ref), 0.0, 1e-15);
  sim.pop_back();
  EXPECT_THROW(trajectory_error(sim, ref), Error);
}

TEST(ImitationError, PoseErrorTakesOutTheRootsOffsetAndLinkDistancesSplitTheMean) {
  const LinkFrames ref = links({Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0, 0, 2)});
  // The whole body 0.5 m off (3-4-5): 0.5 in the world, 0 in posture.
  const LinkFrames moved = links({Vec3(0.3, 0.4, 1), Vec3(1.3, 0.4, 1), Vec3(0.3, 0.4, 2)});
  EXPECT_NEAR(link_position_error(moved, ref), 0.5, 1e-12);
  EXPECT_NEAR(pose_error(moved, ref), 0.0, 1e-12);
  // The root in place, the second link 0.6 m up, the third 0.2 m aside: posture (0.6 + 0.2) / 2
  // over the two links other than the root; world (0 + 0.6 + 0.2) / 3.
  const LinkFrames bent = links({Vec3(0, 0, 1), Vec3(1, 0, 1.6), Vec3(0, 0.2, 2)});
  EXPECT_NEAR(pose_error(bent, ref), 0.4, 1e-12);
  // By link: the root's 0, then the same 0.6 and 0.2 (the root did not move).
  const std::vector<double> dp = pose_distances(bent, ref);
  ASSERT_EQ(dp.size(), 3u);
  EXPECT_NEAR(dp[0], 0.0, 1e-12);
  EXPECT_NEAR(dp[1], 0.6, 1e-12);
  EXPECT_NEAR(dp[2], 0.2, 1e-12);
  EXPECT_NEAR(mean_without_root(dp), 0.4, 1e-12);
  // Shifted as a whole: no link is off in posture, whatever its world distance.
  for (double d : pose_distances(moved, ref)) EXPECT_NEAR(d, 0.0, 1e-12);
  EXPECT_THROW(mean_without_root({0.5}), Error);
  const std::vector<double> d = link_distances(bent, ref);
  ASSERT_EQ(d.size(), 3u);
  EXPECT_NEAR(d[0], 0.0, 1e-12);
  EXPECT_NEAR(d[1], 0.6, 1e-12);
  EXPECT_NEAR(d[2], 0.2, 1e-12);
  EXPECT_NEAR(link_position_error(bent, ref), (d[0] + d[1] + d[2]) / 3, 1e-12);
  // Only the root displaced (0.1 m down): every other link is 0.1 m off relative to it.
  EXPECT_NEAR(pose_error(links({Vec3(0, 0, 0.9), Vec3(1, 0, 1), Vec3(0, 0, 2)}), ref), 0.1, 1e-12);
  EXPECT_THROW(pose_error(links({Vec3::Zero()}), links({Vec3::Zero()})), Error);  // a root alone has no posture
  EXPECT_THROW(pose_error(moved, links({Vec3::Zero(), Vec3::Zero()})), Error);
  EXPECT_THROW(link_distances(moved, links({Vec3::Zero()})), Error);
}

TEST(ImitationError, ProgressIsTheProjectionOnTheReferencesHorizontalDisplacement) {
  EXPECT_DOUBLE_EQ(progress_along(Vec3(1, 1, 0.3), Vec3(2, 0, -0.5)), 0.5);  // heights ignored
  EXPECT_DOUBLE_EQ(progress_along(Vec3(-1, 0, 0), Vec3(2, 0, 0)), -0.5);     // the wrong way
  EXPECT_DOUBLE_EQ(progress_along(Vec3(0, 3, 0), Vec3(0, 2, 0)), 1.5);       // ahead of it
  EXPECT_TRUE(std::isnan(progress_along(Vec3(1, 0, 0), Vec3(0.3, 0.3, 2))));  // under 0.5 m: not measured
}

TEST(ImitationError, ReportsMeanAndSpreadOverTrials) {
  ImitationReport r;
  r.trial_errors = {0.1, 0.3};
  EXPECT_NEAR(r.error_mean(), 0.2, 1e-12);
  EXPECT_NEAR(r.error_std(), 0.1, 1e-12);
  EXPECT_TRUE(std::isnan(r.normalised_return_mean()));
}

// A clip of a lone root: moving along 30 degrees while facing 0, or turning in place to 40.
TEST(ImitationError, TheClipsTravelHeadingIsItsRootsDirectionOverACycle) {
  Skeleton sk;
  Joint root;
  root.name = "root", root.type = JointType::Free;
  sk.joints.push_back(root);
  Clip moving;
  moving.skeleton = sk, moving.fps = 10;
  const Vec3 way(std::cos(kPi / 6), std::sin(kPi / 6), 0);
  for (int f = 0; f < 11; ++f) moving.frames.push_back(rest_pose(sk, Vec3(0, 0, 1) + 0.1 * f * way));
  EXPECT_NEAR(clip_travel_heading(moving, 0.5), kPi / 6, 1e-9);
  EXPECT_NEAR(clip_travel_heading(moving, 0.0), kPi / 6, 1e-9);  // the window held at the ends
  Clip turning = moving;
  for (Pose& p : turning.frames) p.root_pos = Vec3(0, 0, 1), p.rot[0] = heading_rotation(40 * kPi / 180);
  EXPECT_NEAR(clip_travel_heading(turning, 0.5), 40 * kPi / 180, 1e-9);
}

// Commanded along the clip's path, a steered skill's target is the clip's direction of travel at
// every step; an env without a heading goal is refused.
TEST(ImitationError, AlongTheClipSetsTheHeadingGoalToTheClipsTravel) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  const auto walk = test::humanoid3d_motion(ch, "humanoid3d_walk.txt");
  ImitationEnvConfig cfg;
  cfg.goal = ImitationEnvConfig::Goal::Heading;
  cfg.goal_turn = 90;
  cfg.env.max_seconds = 1.0;
  auto env = make_imitation_env(ch, walk, cfg);
  // Each observed target (its angle from the character's heading) against the clip's travel now.
  std::vector<double> misses;
  int goal_at = -1;
  for (const ObservationSlice& part : env->observation_layout())
    if (part.name == "goal") goal_at = part.offset;
  ASSERT_GE(goal_at, 0);
  const PolicyFunction still = [&](const Eigen::VectorXd& x) {
    const double seen = std::atan2(x[goal_at + 1], x[goal_at]);
    const double expected = clip_travel_heading(*walk, env->time()) - heading_angle(env->world().pose().rot[0]);
    misses.push_back(std::abs(std::remainder(seen - expected, 2 * kPi)));
    return Eigen::VectorXd::Zero(env->action_size());
  };
  (void)measure_imitation(*env, still, 1, 2, walk.get(), /*goal_along_clip=*/true);
  EXPECT_NEAR(goal_heading(*env), clip_travel_heading(*walk, env->time()), 1e-12);
  ASSERT_GE(misses.size(), 60u);  // two trials of 1 s
  for (const double m : misses) EXPECT_LT(m, 1e-9);
  // Without it the env draws its own targets, up to 90 degrees off the clip's travel.
  misses.clear();
  (void)measure_imitation(*env, still, 1, 2, walk.get());
  EXPECT_GT(*std::max_element(misses.begin(), misses.end()), 0.1);
  TrackingConfig tc;
  auto tracking = make_tracking_env(ch, walk, tc);
  EXPECT_THROW((void)measure_imitation(*tracking, still, 1, 1, walk.get(), true), Error);
}

TEST(ImitationError, FollowingTheClipBeatsStandingStillOnTheHumanoid) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  const auto walk = test::humanoid3d_motion(ch, "humanoid3d_walk.txt");
  TrackingConfig cfg;
  cfg.env.max_seconds = 2.0;
  auto env = make_tracking_env(ch, walk, cfg);
  // A "policy" that sets the PD targets to the clip's pose one step ahead (it reads the time
  // from the env, not from its input), and one that holds the first frame's pose.
  auto targets = [&](const Pose& p) { return env->action_for(p); };
  CharacterEnv* e = env.get();
  const PolicyFunction follow = [&](const Eigen::VectorXd&) { return targets(walk->sample(e->time() + 1.0 / 30)); };
  const Eigen::VectorXd hold_action = targets(walk->frames[0]);
  const PolicyFunction hold = [&](const Eigen::VectorXd&) { return hold_action; };
  const ImitationReport good = measure_imitation(*env, follow, 1, 4);
  const ImitationReport bad = measure_imitation(*env, hold, 1, 4);
  ASSERT_EQ(good.trial_errors.size(), 4u);
  EXPECT_NEAR(good.cycle_seconds, std::round(walk->duration() * 30) / 30, 1e-9);
  EXPECT_LT(good.error_mean(), bad.error_mean());
  EXPECT_GT(bad.error_mean(), 0.1);  // standing while the reference walks away
  // Tracking episodes have a known best: normalised returns lie in (0, 1], better when following.
  ASSERT_EQ(good.trial_returns.size(), 4u);
  EXPECT_GT(good.normalised_return_mean(), bad.normalised_return_mean());
  EXPECT_LE(good.normalised_return_mean(), 1.0);
  // The walk moves (about 1 m/s): progress is measured in every trial. Holding a pose, the
  // character pitches forward on the start's momentum and falls within a second of the 2 s
  // episode: it covers well under the reference's ground (measured 0.40).
  ASSERT_EQ(bad.trial_progress.size(), 4u);
  EXPECT_GT(bad.progress_mean(), 0.0);
  EXPECT_LT(bad.progress_mean(), 0.6);
  // Per link: one per joint, named, averaging to the error; the root's is the root's own distance.
  ASSERT_EQ(bad.link_errors.size(), static_cast<std::size_t>(ch.skeleton.num_joints()));
  ASSERT_EQ(bad.link_names.size(), bad.link_errors.size());
  EXPECT_EQ(bad.link_names[0], ch.skeleton.joints[0].name);
  double sum = 0;
  for (double link : bad.link_errors) sum += link;
  EXPECT_NEAR(sum / static_cast<double>(bad.link_errors.size()), bad.error_mean(), 1e-9);
  // Posture: the reference walks away, which the pose error takes out; what is left is the
  // fallen character's posture, and following the clip keeps it small.
  ASSERT_EQ(bad.trial_pose_errors.size(), 4u);
  EXPECT_LT(bad.pose_error_mean(), bad.error_mean());
  EXPECT_LT(good.pose_error_mean(), bad.pose_error_mean());
  // Posture by link: the root's is 0 and the others average to the pose error.
  ASSERT_EQ(bad.link_pose_errors.size(), bad.link_errors.size());
  EXPECT_EQ(bad.link_pose_errors[0], 0.0);
  EXPECT_NEAR(mean_without_root(bad.link_pose_errors), bad.pose_error_mean(), 1e-9);
  // Per step of the cycle: one value a step (the walk loops: every trial reaches every step),
  // averaging to the error; the character holding still falls behind, so its error grows.
  ASSERT_EQ(bad.step_errors.size(), static_cast<std::size_t>(std::lround(good.cycle_seconds * 30)));
  ASSERT_EQ(bad.step_pose_errors.size(), bad.step_errors.size());
  double steps = 0;
  for (double step : bad.step_errors) steps += step;
  EXPECT_NEAR(steps / static_cast<double>(bad.step_errors.size()), bad.error_mean(), 1e-9);
  EXPECT_LT(bad.step_errors.front(), 0.05);  // one step after a start on the clip
  EXPECT_GT(bad.step_errors.back(), 3 * bad.step_errors.front());
  // A clip that does not fit, and no clip at all, are errors.
  Clip other = *walk;
  other.skeleton.joints.pop_back();
  EXPECT_THROW(measure_imitation(*env, hold, 1, 2, &other), Error);
  EXPECT_THROW(measure_imitation(*env, hold, 1, 0), Error);
}

// Without early termination a collapsing character ends no episode, so it never counts as a
// fall; lying with its root below half the reference's for 10 frames counts as down.
TEST(ImitationError, ACollapseWithoutATerminationCountsAsDownNotAsAFall) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  const auto walk = test::humanoid3d_motion(ch, "humanoid3d_walk.txt");
  TrackingConfig cfg;
  cfg.env.max_seconds = 3.0;
  cfg.env.early_termination = false;
  cfg.env.fall_height = 0;
  auto env = make_tracking_env(ch, walk, cfg);
  CharacterEnv* e = env.get();
  const PolicyFunction follow = [&](const Eigen::VectorXd&) { return e->action_for(walk->sample(e->time() + 1.0 / 30)); };
  const Eigen::VectorXd fold_action = env->action_for(test::folded(ch, walk->frames[0]));
  const PolicyFunction fold = [&](const Eigen::VectorXd&) { return fold_action; };
  const ImitationReport bad = measure_imitation(*env, fold, 1, 3);
  // Open-loop PD following stays up for about a second before it topples: a 0.6 s episode.
  cfg.env.max_seconds = 0.6;
  env = make_tracking_env(ch, walk, cfg);
  e = env.get();
  const ImitationReport good = measure_imitation(*env, follow, 1, 3);
  EXPECT_EQ(good.falls, 0);
  EXPECT_EQ(good.down, 0);
  EXPECT_EQ(bad.falls, 0);  // nothing ends its episodes
  EXPECT_EQ(bad.down, 3);
}

// max_drift is a training rule: a trial goes on through it, so the protocol's figures are those
// of the same env without the rule (here a held pose that the walk leaves behind within a second).
TEST(ImitationError, ADriftTerminationDoesNotEndATrialOrCountAsAFall) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  const auto walk = test::humanoid3d_motion(ch, "humanoid3d_walk.txt");
  auto measure = [&](double max_drift) {
    TrackingConfig cfg;
    cfg.env.max_seconds = 2.0;
    cfg.env.max_drift = max_drift;
    auto env = make_tracking_env(ch, walk, cfg);
    const Eigen::VectorXd hold_action = env->action_for(walk->frames[0]);
    return measure_imitation(*env, [&](const Eigen::VectorXd&) { return hold_action; }, 1, 3);
  };
  const ImitationReport with = measure(0.2), without = measure(0.0);
  EXPECT_EQ(with.trial_errors, without.trial_errors);
  EXPECT_EQ(with.trial_returns, without.trial_returns);
  EXPECT_EQ(with.trial_progress, without.trial_progress);
  EXPECT_EQ(with.falls, without.falls);
  EXPECT_EQ(with.down, without.down);
}

TEST(Robustness, HeavyCubesFellAStandingHumanoidSoonerThanNone) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  // No reference: trials start standing in the rest pose, which zero PD targets hold.
  auto frames = [&](double mass) {
    CharacterEnvConfig cfg;
    cfg.max_seconds = 10.0;
    cfg.projectiles.enabled = mass > 0;
    cfg.projectiles.mass = mass;
    cfg.projectiles.speed = 1.0;  // seed 004's 0.2 m/s barely moves a character standing still
    CharacterEnv env(ch, cfg);
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(env.action_size());
    const PolicyFunction act = [&](const Eigen::VectorXd&) { return zero; };
    EXPECT_THROW(measure_robustness(env, act, 1, 0, 120), Error);
    return measure_robustness(env, act, 1, 3, 120);
  };
  const RobustnessReport none = frames(0.0), heavy = frames(20.0);
  ASSERT_EQ(none.frames.size(), 3u);
  EXPECT_EQ(none.max_frames, 120);
  EXPECT_EQ(none.mean(), 120.0);  // standing, untouched, to the end
  for (double f : heavy.frames) EXPECT_LT(f, 110.0);  // each heavy trial ends lying down
}
