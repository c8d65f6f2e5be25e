// Pushes (impulse = force * duration) and seed 004's projectile test (cubes launched at the
// torso: straight flight at the set speed from the set distance, hits, recycling, and heavy cubes
// toppling a standing humanoid sooner than light ones).
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <memory>

#include "core/error.hpp"
#include "env/character_env.hpp"
#include "motion/builtin.hpp"
#include "motion/deepmimic.hpp"
#include "humanoid_data.hpp"

using namespace mimic;

namespace {

const CharacterModel& builtin() {
  static const CharacterModel ch = CharacterModel::from_skeleton(builtin_humanoid(), "builtin");
  return ch;
}

// DeepMimic's humanoid: it stands with zero actions (PD targets = its rest pose).
const CharacterModel& humanoid() {
  static const CharacterModel ch = test::humanoid3d();
  return ch;
}

InitState standing_at(const CharacterModel& ch, const Vec3& root) {
  InitState s{rest_pose(ch.skeleton, root), PoseVelocity{}, 0.0, {}};
  s.velocity.joint_ang.assign(ch.skeleton.joints.size(), Vec3::Zero());
  return s;
}

// Linear momentum of the whole character (kg m/s).
Vec3 momentum(const World& w) {
  mjModel* m = w.model();
  mjData* d = w.data();
  mj_forward(m, d);
  mj_subtreeVel(m, d);
  const int root = mj_name2id(m, mjOBJ_BODY, "root");
  return m->body_subtreemass[root] * Vec3(d->subtree_linvel[3 * root], d->subtree_linvel[3 * root + 1], d->subtree_linvel[3 * root + 2]);
}

// Position of a free body from qpos (xpos lags one physics step behind after mj_step).
Vec3 body_pos(const World& w, int body) {
  const mjtNum* p = w.data()->qpos + w.model()->jnt_qposadr[w.model()->body_jntadr[body]];
  return Vec3(p[0], p[1], p[2]);
}

}  // namespace

TEST(Push, ImpulseIsForceTimesDuration) {
  // Weightless and airborne: only the push changes the momentum (joint torques are internal).
  CharacterEnvConfig cfg;
  const Vec3 force(120.0, -40.0, 30.0);
  cfg.pushes = {PushSpec{"root", force, 0.05, 0.5}};  // starts and ends inside control steps
  CharacterEnv env(builtin(), cfg);
  for (int k = 0; k < 3; ++k) env.world().model()->opt.gravity[k] = 0;
  env.reset(standing_at(builtin(), Vec3(0, 0, 5)));
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(env.action_size());
  const double dt = 1.0 / cfg.sim.control_hz;
  env.step(zero);
  EXPECT_LT(momentum(env.world()).norm(), 1e-9);  // [0, dt): before the push
  env.step(zero);
  // Part of [dt, 2dt). (Joint armature holds a little momentum that no body mass shows: 1e-3.)
  EXPECT_TRUE(momentum(env.world()).isApprox(force * (2 * dt - 0.05), 1e-3)) << momentum(env.world()).transpose();
  for (int i = 0; i < 25; ++i) env.step(zero);
  EXPECT_TRUE(momentum(env.world()).isApprox(force * 0.5, 0.01)) << momentum(env.world()).transpose();
  // The next episode is pushed again, from its own start.
  env.reset(standing_at(builtin(), Vec3(0, 0, 5)));
  for (int i = 0; i < 27; ++i) env.step(zero);
  EXPECT_TRUE(momentum(env.world()).isApprox(force * 0.5, 0.01));
}

TEST(Push, SidewaysPushKnocksAStandingCharacterOver) {
  MIMIC_NEED_HUMANOID();
  CharacterEnvConfig cfg;
  cfg.early_termination = false;
  CharacterEnv env(humanoid(), cfg);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(env.action_size());
  auto lean_after = [&](double newtons) {
    env.set_pushes({PushSpec{"chest", Vec3(0, newtons, 0), 0.2, 0.3}});
    std::mt19937_64 rng(1);
    env.reset(rng);
    for (int i = 0; i < 45; ++i) env.step(zero);
    return env.world().pose().root_pos.z();
  };
  EXPECT_LT(lean_after(600.0), 0.6 * lean_after(0.0));
  EXPECT_THROW(env.set_pushes({PushSpec{"tail", Vec3(1, 0, 0), 0, 1}}), Error);
}

TEST(Projectile, FliesStraightAtTheSetSpeedFromTheSetDistanceAndHitsTheChest) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel& ch = humanoid();
  ProjectileSpec spec;  // seed 004: 0.2 m cubes at 0.2 m/s
  spec.enabled = true;
  spec.mass = 2.0;
  MjcfOptions opts;
  ProjectileLauncher::add_to(opts, spec, 30.0);
  World w(ch, SimConfig{}, opts);
  ProjectileLauncher launcher(w, spec);
  w.set_state(standing_at(ch, Vec3(0, 0, ch.rest_root_height() + 1e-3)).pose);
  launcher.reset(w);
  const mjModel* m = w.model();
  const int chest = mj_name2id(m, mjOBJ_BODY, "chest"), chest_geom = m->body_geomadr[chest];
  const Vec3 aim(w.data()->geom_xpos[3 * chest_geom], w.data()->geom_xpos[3 * chest_geom + 1], w.data()->geom_xpos[3 * chest_geom + 2]);
  const Vec3 dir(1, 0, 0);  // from the front
  const int k = launcher.launch(w, aim, dir);
  const int cube = launcher.body(k);
  // Seed 004 section 6.4: a cube 0.2 m on a side (box half-sizes 0.1), of the set mass, at 0.2 m/s.
  EXPECT_DOUBLE_EQ(spec.size, 0.2);
  EXPECT_DOUBLE_EQ(spec.speed, 0.2);
  const int cube_geom = m->body_geomadr[cube];
  EXPECT_EQ(m->body_geomnum[cube], 1);
  EXPECT_EQ(m->geom_type[cube_geom], mjGEOM_BOX);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(m->geom_size[3 * cube_geom + i], 0.1, 1e-12);
  EXPECT_NEAR(m->body_mass[cube], 2.0, 1e-9);
  mj_forward(m, w.data());
  const Vec3 start = body_pos(w, cube);
  EXPECT_NEAR((start - aim).norm(), spec.distance, 1e-9);
  // Straight at 0.2 m/s despite gravity; contact when the cube's face meets the chest sphere.
  const double dt = 1.0 / 30.0, reach = m->geom_size[3 * chest_geom] + spec.size / 2;
  const int expected = static_cast<int>(std::ceil((spec.distance - reach) / spec.speed / dt));
  int hit_step = -1;
  double gap_at_hit = 0;
  for (int i = 1; i <= expected + 10 && hit_step < 0; ++i) {
    w.step();
    launcher.after_step(w);
    if (i == 10) {
      const Vec3 p = body_pos(w, cube);
      EXPECT_NEAR((p - start).norm(), spec.speed * 10 * dt, 1e-6);
      EXPECT_NEAR(p.z(), start.z(), 1e-9);
      EXPECT_TRUE(launcher.flying(k));
    }
    if (launcher.stats().hits == 1) {
      hit_step = i;
      const Vec3 chest_now(w.data()->geom_xpos[3 * chest_geom], w.data()->geom_xpos[3 * chest_geom + 1], w.data()->geom_xpos[3 * chest_geom + 2]);
      gap_at_hit = (body_pos(w, cube) - chest_now).norm();
    }
  }
  // Touching when reported (centres one reach apart, give or take one step's travel); on time,
  // allowing for the standing humanoid's sway (a few centimetres over the 1.5 s flight).
  EXPECT_NEAR(gap_at_hit, reach, spec.speed * dt + 2e-3);
  EXPECT_GE(hit_step, expected - 2);
  EXPECT_LE(hit_step, expected + 8);
  EXPECT_EQ(launcher.stats().launched, 1);
  EXPECT_EQ(launcher.stats().misses, 0);
  EXPECT_FALSE(launcher.flying(k));
}

TEST(Projectile, ABodyWithoutAChestIsAimedAtItsRootAndAMissingNamedLinkIsAnError) {
  Skeleton sk = builtin_humanoid();
  sk.joints[static_cast<std::size_t>(sk.find("chest"))].name = "torso";
  const CharacterModel ch = CharacterModel::from_skeleton(sk, "no_chest");
  ProjectileSpec spec;
  spec.enabled = true;
  MjcfOptions opts;
  ProjectileLauncher::add_to(opts, spec, 30.0);
  World w(ch, SimConfig{}, opts);
  EXPECT_EQ(ProjectileLauncher(w, spec).spec().target, "root");
  spec.target = "tail";
  try {
    ProjectileLauncher launcher(w, spec);
    ADD_FAILURE() << "a link the character lacks was aimed at";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("character 'no_chest' has no link 'tail' with a geom to aim at"), std::string::npos) << e.what();
  }
}

TEST(Projectile, AMissFallsAndIsParkedAfterItsLinger) {
  ProjectileSpec spec;
  spec.enabled = true;
  spec.speed = 0.9;  // the flight's end falls inside a control step
  MjcfOptions opts;
  ProjectileLauncher::add_to(opts, spec, 30.0);
  World w(builtin(), SimConfig{}, opts);
  ProjectileLauncher launcher(w, spec);
  launcher.reset(w);
  const int k = launcher.launch(w, Vec3(3, 3, 1.5), Vec3(0, 1, 0));  // empty air, 3 m from the character
  const double dt = 1.0 / 30.0;
  const int flight = static_cast<int>((spec.distance - spec.size / 2) / spec.speed / dt);  // whole steps in flight
  for (int i = 0; i < flight; ++i) w.step(), launcher.after_step(w);
  EXPECT_TRUE(launcher.flying(k));
  w.step(), launcher.after_step(w);
  EXPECT_FALSE(launcher.flying(k));
  EXPECT_EQ(launcher.stats().misses, 1);
  EXPECT_EQ(launcher.stats().hits, 0);
  const double z0 = body_pos(w, launcher.body(k)).z();
  for (int i = 0; i < 5; ++i) w.step(), launcher.after_step(w);
  EXPECT_LT(body_pos(w, launcher.body(k)).z(), z0 - 0.1);  // falling once its flight is over
  for (int i = 0; i < 15; ++i) w.step(), launcher.after_step(w);
  EXPECT_GT(body_pos(w, launcher.body(k)).norm(), 100.0);  // parked far away after `linger`
}

TEST(Projectile, EveryFrameProtocolRecyclesAFixedPool) {
  MIMIC_NEED_HUMANOID();
  CharacterEnvConfig cfg;
  cfg.early_termination = false;
  cfg.projectiles.enabled = true;
  cfg.projectiles.mass = 0.1;
  CharacterEnv env(humanoid(), cfg);
  const ProjectileLauncher& p = *env.projectiles();
  EXPECT_EQ(p.pool_size(), projectile_pool_size(cfg.projectiles, cfg.sim.control_hz));
  // The cubes are parked a kilometre away, but a picture is framed on the character: MuJoCo's
  // near clipping plane (0.01 of the extent) would otherwise be 10 m away and cut it out.
  EXPECT_DOUBLE_EQ(env.world().model()->stat.extent, 3.0);
  std::mt19937_64 rng(5);
  env.reset(rng);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(env.action_size());
  const int steps = p.pool_size() + 30;  // more launches than cubes
  for (int i = 0; i < steps; ++i) env.step(zero);
  EXPECT_EQ(p.stats().launched, steps);
  EXPECT_GT(p.stats().hits, steps / 2);  // aimed inside the torso: most arrive
  EXPECT_LE(p.stats().hits + p.stats().misses, steps);
  // A new episode starts with no cubes out and fresh counts; every 3rd step launches 1 in 3.
  env.reset(rng);
  EXPECT_EQ(p.stats().launched, 0);
  for (int k = 0; k < p.pool_size(); ++k) EXPECT_GT(body_pos(env.world(), p.body(k)).norm(), 100.0);
  CharacterEnvConfig third = cfg;
  third.projectiles.every = 3;
  CharacterEnv env3(humanoid(), third);
  env3.reset(rng);
  for (int i = 0; i < 10; ++i) env3.step(zero);
  EXPECT_EQ(env3.projectiles()->stats().launched, 4);  // steps 0, 3, 6, 9
  // every: 0 launches only when asked, from a pool of 4 that the oldest flight gives way in.
  CharacterEnvConfig asked = cfg;
  asked.projectiles.every = 0;
  CharacterEnv env0(humanoid(), asked);
  ProjectileLauncher& launcher = *env0.projectiles();
  EXPECT_EQ(launcher.pool_size(), 4);
  env0.reset(rng);
  for (int i = 0; i < 10; ++i) env0.step(zero);
  EXPECT_EQ(launcher.stats().launched, 0);
  const int k = launcher.launch(env0.world(), launcher.sample_aim(env0.world()), launcher.sample_direction());
  EXPECT_TRUE(launcher.flying(k));
  env0.step(zero);
  EXPECT_EQ(launcher.stats().launched, 1);
  asked.projectiles.every = -1;
  EXPECT_THROW(CharacterEnv(humanoid(), asked), Error);
  third.projectiles.target = "tail";
  EXPECT_THROW(CharacterEnv(humanoid(), third), Error);
}

TEST(Projectile, HeavyCubesToppleAStandingHumanoidSoonerThanLightOnes) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel& ch = humanoid();
  // Frames until the root drops below 0.5 m (lying, possibly on cubes) or a fall, of 120.
  auto frames_survived = [&](double mass, std::uint64_t seed) {
    CharacterEnvConfig cfg;
    cfg.max_seconds = 4.0;
    cfg.projectiles.enabled = mass > 0;
    cfg.projectiles.mass = mass;
    cfg.projectiles.speed = 1.0;  // seed 004's 0.2 m/s barely moves a character that stands still
    CharacterEnv env(ch, cfg);
    std::mt19937_64 rng(seed);
    env.reset(rng);
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(env.action_size());
    int n = 0;
    for (StepResult r; !r.done() && env.world().pose().root_pos.z() > 0.5; ++n) r = env.step(zero);
    return n;
  };
  int heavy = 0;
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    EXPECT_EQ(frames_survived(0.0, seed), 120);
    EXPECT_EQ(frames_survived(0.2, seed), 120);
    heavy += frames_survived(20.0, seed);
  }
  EXPECT_LT(heavy, 3 * 100);
}
