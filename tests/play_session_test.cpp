// The interactive session (control/play_session): pushes and cubes through the controller, and
// the session's events on the committed humanoid skills: a request taken over, a push that floors
// the character, recovery handing over and back.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include <mujoco/mujoco.h>

#include "control/play_session.hpp"
#include "error_message.hpp"
#include "motion/clip_io.hpp"
#include "motion/kinematics.hpp"
#include "mimic/runtime.hpp"
#include "test_data.hpp"

using namespace mimic;
using test::error_of;

namespace {

const std::filesystem::path kModels = std::filesystem::path(MIMIC_SOURCE_DIR) / "models";

TEST(PlaySession, APushMovesTheRootAlongItAndACubeIsThrownOnlyWhereTheWorldHasCubes) {
  std::filesystem::path data;
  MIMIC_REQUIRE_SHARED("deepmimic/characters/humanoid3d.txt", data);
  const auto walk = Skill::load(kModels / "humanoid_walk_iccgan", "walk");
  // The same start twice; one is pushed sideways (+y) for 0.2 s from step 10.
  auto lateral_after = [&](bool pushed) {
    Controller c({walk}, 4);
    for (int i = 0; i < 10; ++i) (void)c.step();
    const double y0 = c.root_position().y();
    if (pushed) c.push(Eigen::Vector3d(0, 400, 0), 0.2);
    for (int i = 0; i < 8; ++i) (void)c.step();
    return c.root_position().y() - y0;
  };
  const double free = lateral_after(false), pushed = lateral_after(true);
  // 400 N for 0.2 s is 80 N s on a 45 kg body: ~1.8 m/s, about 0.1 m within the 8 steps.
  EXPECT_GT(pushed - free, 0.08) << "free " << free << ", pushed " << pushed;
  Controller c({walk}, 4);
  EXPECT_FALSE(c.throw_cube());  // the model's world has no cubes
  EXPECT_NE(error_of([&] { c.push(Eigen::Vector3d(std::nan(""), 0, 0), 0.2); }).find("finite"), std::string::npos);
  EXPECT_NE(error_of([&] { c.push(Eigen::Vector3d(1, 0, 0), -1); }).find("seconds >= 0"), std::string::npos);
  // With cubes on demand: none flies until one is thrown.
  const auto armed = Skill::load(kModels / "humanoid_walk_iccgan", "walk", {"env.projectiles={enabled: true, every: 0, mass: 20, speed: 6}"});
  Controller with({armed}, 4);
  for (int i = 0; i < 5; ++i) (void)with.step();
  EXPECT_TRUE(with.throw_cube());
}

TEST(PlaySession, ARequestIsTakenOverAndLoggedAndAFloorPushStartsTheRecovery) {
  std::filesystem::path data;
  MIMIC_REQUIRE_SHARED("deepmimic/characters/humanoid3d.txt", data);
  const auto walk = Skill::load(kModels / "humanoid_walk_iccgan", "walk");
  const auto run = Skill::load(kModels / "humanoid_run_iccgan_straight_loop", "run");
  PlayOptions o;
  o.rule.threshold = -1.0;  // any state: the request is granted on the next step
  PlaySession session({walk, run}, o);
  EXPECT_EQ(session.wanted(), "walk");
  ASSERT_EQ(session.scores().size(), 2u);
  for (double s : session.scores()) EXPECT_TRUE(s >= -1 && s <= 1) << s;
  EXPECT_FALSE(session.request(2));  // no third skill
  for (int i = 0; i < 30; ++i) session.step();
  EXPECT_TRUE(session.request(1));
  session.step();
  EXPECT_EQ(session.controller().skill(), "run");
  ASSERT_GE(session.events().size(), 2u);
  const PlayEvent& request = session.events()[session.events().size() - 2];
  const PlayEvent& taken = session.events().back();
  EXPECT_EQ(request.event, "request");
  EXPECT_EQ(request.skill, "run");
  EXPECT_NEAR(request.t, 30.0 / 30.0, 1e-9);
  EXPECT_EQ(taken.event, "switch");
  EXPECT_EQ(taken.skill, "run");
  EXPECT_NEAR(taken.t, 31.0 / 30.0, 1e-9);
  EXPECT_NE(error_of([&] { PlayOptions bad; bad.recovery = {"getup"}; PlaySession s({walk, run}, bad); }).find("no skill 'getup'"),
            std::string::npos);

  // Recovery: with the walk as the "get-up" (what matters is the hand-over, not the getting up), a
  // push hard enough to floor the runner makes the character down, the recovery skill takes it at
  // once, and the run is asked for again.
  PlayOptions r;
  r.recovery = {"walk"};
  r.push_force = 3000;
  r.push_seconds = 0.3;
  PlaySession fall({run, walk}, r);
  for (int i = 0; i < 10; ++i) fall.step();
  fall.push(Eigen::Vector3d(0, 1, 0));
  bool recovering = false;
  for (int i = 0; i < 150 && !recovering; ++i) {
    fall.step();
    recovering = fall.recovering();
  }
  ASSERT_TRUE(recovering) << "3000 N for 0.3 s floors the character within 5 s";
  EXPECT_EQ(fall.controller().skill(), "walk");
  EXPECT_EQ(fall.wanted(), "run");
  EXPECT_EQ(fall.controller().requested(), "") << "the run is asked for once the get-up is done, not before";
  std::vector<std::string> kinds;
  for (const PlayEvent& e : fall.events()) kinds.push_back(e.event);
  ASSERT_GE(kinds.size(), 3u);
  EXPECT_EQ(kinds[kinds.size() - 3], "push");
  EXPECT_EQ(kinds[kinds.size() - 2], "down");
  EXPECT_EQ(kinds.back(), "recovering");
  EXPECT_EQ(fall.events().back().skill, "walk");
}

TEST(PlaySession, RecoveryHandsTheCharacterToTheGetUpOfTheSideItLiesOnAndSwitchesWhenItRollsOver) {
  std::filesystem::path down_clip, up_clip;
  MIMIC_REQUIRE_SHARED("deepmimic/motions/humanoid3d_getup_facedown.txt", down_clip);
  MIMIC_REQUIRE_SHARED("deepmimic/motions/humanoid3d_getup_faceup.txt", up_clip);
  // Stand-ins for the get-ups: the walk's networks with a get-up clip each (the side is read from
  // the clip's first frame); listed face-up first, so that a choice by order would pick it.
  const auto walk = Skill::load(kModels / "humanoid_walk_iccgan", "walk");
  const auto up = Skill::load(kModels / "humanoid_walk_iccgan", "up", {"env.clip=" + up_clip.string()});
  const auto down = Skill::load(kModels / "humanoid_walk_iccgan", "down", {"env.clip=" + down_clip.string()});
  PlayOptions o;
  o.recovery = {"up", "down"};
  // The character laid on the ground, still, its pose otherwise the walk's start: the root's
  // forward axis (+x) turned about y onto +z (face up) or -z (face down), MuJoCo's w, x, y, z.
  auto lay = [](PlaySession& s, int side) {
    Controller& c = s.controller();
    Eigen::VectorXd qpos = Eigen::Map<const Eigen::VectorXd>(c.physics_data()->qpos, c.physics_model()->nq);
    qpos[2] = 0.15;
    qpos.segment<4>(3) << std::sqrt(0.5), 0.0, -side * std::sqrt(0.5), 0.0;
    c.start(c.skill(), qpos, Eigen::VectorXd::Zero(c.physics_model()->nv));
    EXPECT_EQ(c.lying_side(), side);
  };
  for (int side : {1, -1}) {
    PlaySession s({walk, up, down}, o);
    EXPECT_EQ(s.controller().lying_side(), 0);  // standing
    lay(s, side);
    for (int i = 0; i < 15 && !s.recovering(); ++i) s.step();
    ASSERT_TRUE(s.recovering()) << "lying for 10 frames is down";
    EXPECT_EQ(s.controller().skill(), side > 0 ? "up" : "down");
    EXPECT_EQ(s.events().back().event, "recovering");
    EXPECT_EQ(s.wanted(), "walk");
  }
  // Face up, taken by the face-up get-up, then rolled onto its front: after the down rule's 10
  // frames on that side (not before) the face-down get-up takes over, and the walk is still asked for.
  PlaySession s({walk, up, down}, o);
  lay(s, 1);
  while (!s.recovering()) s.step();
  ASSERT_EQ(s.controller().skill(), "up");
  lay(s, -1);
  for (int i = 0; i < 9; ++i) s.step();
  EXPECT_EQ(s.controller().skill(), "up") << "9 frames on the other side are not enough";
  for (int i = 0; i < 3 && s.controller().skill() == "up"; ++i) s.step();
  EXPECT_EQ(s.controller().skill(), "down");
  EXPECT_EQ(s.events().back().event, "recovering");
  EXPECT_EQ(s.events().back().skill, "down");
  EXPECT_EQ(s.wanted(), "walk");
}

TEST(PlaySession, TheSkillAskedForTakesTheCharacterBackOnlyOnceTheGetUpIsDone) {
  std::filesystem::path up_clip;
  MIMIC_REQUIRE_SHARED("deepmimic/motions/humanoid3d_getup_faceup.txt", up_clip);
  // The stand-in get-up: the walk's networks with the face-up get-up clip (3.77 s). Laid on its
  // back, the character goes down and the stand-in takes it; then it is given back the walking
  // state it had (as if got up): up by the down rule after 10 steps, but the get-up is done only
  // 3.77 s after it took over, and the walk is asked for then, taking over at once (threshold -1).
  const auto walk = Skill::load(kModels / "humanoid_walk_iccgan", "walk");
  const auto up = Skill::load(kModels / "humanoid_walk_iccgan", "up", {"env.clip=" + up_clip.string()});
  PlayOptions o;
  o.recovery = {"up"};
  PlaySession s({walk, up}, o);
  for (int i = 0; i < 20; ++i) s.step();
  Controller& c = s.controller();
  const Eigen::VectorXd walking_q = Eigen::Map<const Eigen::VectorXd>(c.physics_data()->qpos, c.physics_model()->nq);
  const Eigen::VectorXd walking_v = Eigen::Map<const Eigen::VectorXd>(c.physics_data()->qvel, c.physics_model()->nv);
  Eigen::VectorXd lying = walking_q;
  lying[2] = 0.15;
  lying.segment<4>(3) << std::sqrt(0.5), 0.0, -std::sqrt(0.5), 0.0;
  c.start("walk", lying, Eigen::VectorXd::Zero(c.physics_model()->nv));
  while (!s.recovering()) s.step();
  ASSERT_EQ(c.skill(), "up");
  const double took = s.time();
  c.start("up", walking_q, walking_v);
  for (int i = 0; i < 15; ++i) s.step();
  ASSERT_FALSE(s.down()) << "walking again for 15 steps: up";
  EXPECT_TRUE(s.recovering());
  EXPECT_EQ(c.requested(), "") << "up, but the get-up has had it " << s.time() - took << " s of its 3.77";
  while (s.recovering() && s.time() < took + 5.0) s.step();
  EXPECT_FALSE(s.recovering());
  EXPECT_EQ(c.skill(), "walk");
  ASSERT_GE(s.events().size(), 2u);
  EXPECT_EQ(s.events().back().event, "recovered");
  const double back = s.events().back().t;
  EXPECT_GE(back, took + 3.77 - 1e-9);
  EXPECT_LE(back, took + 3.77 + 2.0 / 30.0) << "at once when done (the request, then the take-over a step later)";

  // A stand-in whose clip ends where a walking character never stands is never done: laid down,
  // taken by it, then given the walking state, the character is up for 4.5 s and not handed back.
  // Returns the character's highest joint 15 steps into the walking state.
  auto never_done = [&](const Clip& clip, const std::string& file) {
    const std::filesystem::path path = test::temp_dir("play_session_" + file) / (file + ".mclip");
    save_clip(clip, path);
    const auto stand_in = Skill::load(kModels / "humanoid_walk_iccgan", "up", {"env.clip=" + path.string()});
    PlaySession t({walk, stand_in}, o);
    Controller& tc = t.controller();
    tc.start("walk", lying, Eigen::VectorXd::Zero(tc.physics_model()->nv));
    while (!t.recovering()) t.step();
    const double stand_in_took = t.time();
    tc.start("up", walking_q, walking_v);
    for (int i = 0; i < 15; ++i) t.step();
    const double top = tc.highest_joint_height();
    while (t.time() < stand_in_took + 4.5) t.step();
    EXPECT_TRUE(t.recovering()) << file;
    EXPECT_EQ(tc.skill(), "up") << file;
    EXPECT_FALSE(t.down()) << file;
    EXPECT_EQ(tc.requested(), "") << file;
    return top;
  };
  // The clip ends with the root 2 m up: standing means at least 80 % of that.
  Clip tall = load_motion(up_clip);
  tall.frames.back().root_pos.z() = 2.0;
  (void)never_done(tall, "tall_getup");
  // The clip ends at the walk's root height but with the arms raised overhead (the shoulders
  // turned half a turn about the forward axis): its highest joint, a wrist, is above the walking
  // character's highest (the neck) by more than a quarter, so the root's height alone does not make
  // it done.
  Clip reach = load_motion(up_clip);
  const LinkFrames hanging = forward_kinematics(reach.skeleton, reach.frames.back());
  for (const char* shoulder : {"right_shoulder", "left_shoulder"})
    reach.frames.back().rot[static_cast<std::size_t>(reach.skeleton.find(shoulder))] = Quat(Eigen::AngleAxisd(std::numbers::pi, Vec3::UnitX()));
  const LinkFrames raised = forward_kinematics(reach.skeleton, reach.frames.back());
  auto top = [](const LinkFrames& f) { double z = 0; for (const Vec3& p : f.joint_pos) z = std::max(z, p.z()); return z; };
  ASSERT_GT(top(raised), top(hanging) / 0.8) << "the raised wrists " << top(raised) << " m, the clip's own end " << top(hanging) << " m";
  const double walking_top = never_done(reach, "reach_getup");
  EXPECT_GT(walking_top, 1.2) << "a walking character's neck";
  EXPECT_LT(walking_top, 0.8 * top(raised));
}

}  // namespace
