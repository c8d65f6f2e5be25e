// The simulated DeepMimic humanoid on MuJoCo: generated model, state round trip, standing.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cmath>

#include "core/error.hpp"
#include "motion/bvh.hpp"
#include "motion/builtin.hpp"
#include "motion/deepmimic.hpp"
#include "motion/kinematics.hpp"
#include "sim/character_model.hpp"
#include "sim/world.hpp"
#include "humanoid_data.hpp"

using namespace mimic;

namespace {

// Lowest and highest z over a set of the model's geoms (world frame, exact for each shape).
std::pair<double, double> geom_z_range(const World& w, const std::vector<std::string>& only = {}) {
  const mjModel* m = w.model();
  const mjData* d = w.data();
  double lo = 1e9, hi = -1e9;
  for (int g = 0; g < m->ngeom; ++g) {
    if (m->geom_bodyid[g] == 0) continue;  // the floor
    const std::string name = mj_id2name(m, mjOBJ_GEOM, g) ? mj_id2name(m, mjOBJ_GEOM, g) : "";
    if (!only.empty() && std::find(only.begin(), only.end(), name) == only.end()) continue;
    const double* size = m->geom_size + 3 * g;
    const double* R = d->geom_xmat + 9 * g;  // row-major; R[6..8] is the world z row
    const double z = d->geom_xpos[3 * g + 2];
    double h = 0;
    switch (m->geom_type[g]) {
      case mjGEOM_SPHERE: h = size[0]; break;
      case mjGEOM_CAPSULE: h = size[0] + size[1] * std::abs(R[8]); break;
      case mjGEOM_BOX: h = size[0] * std::abs(R[6]) + size[1] * std::abs(R[7]) + size[2] * std::abs(R[8]); break;
      default: h = m->geom_rbound[g];
    }
    lo = std::min(lo, z - h);
    hi = std::max(hi, z + h);
  }
  return {lo, hi};
}

Clip walk_clip(const CharacterModel& ch) {
  return load_deepmimic_motion(test::shared_data() / "deepmimic/motions/humanoid3d_walk.txt", ch.skeleton);
}

}  // namespace

TEST(SimCharacter, MassAndStandingHeightMatchTheFile) {
  std::filesystem::path p;
  MIMIC_REQUIRE_SHARED("deepmimic/characters/humanoid3d.txt", p);
  const CharacterModel ch = test::humanoid3d();
  World w(ch);
  EXPECT_NEAR(mj_getTotalmass(w.model()), 45.0, 0.45);  // the file's masses sum to 45 kg
  EXPECT_NEAR(ch.total_mass(), 45.0, 1e-9);
  w.set_state(rest_pose(ch.skeleton, Vec3(0, 0, 1)));
  const auto [lo, hi] = geom_z_range(w);
  EXPECT_NEAR(hi - lo, ch.rest_height(), 0.01 * ch.rest_height());
  EXPECT_NEAR(hi - lo, 1.62, 0.0162);  // DeepMimic's humanoid is 1.62 m tall
  EXPECT_EQ(w.model()->nv, 34);        // 34 degrees of freedom
  EXPECT_EQ(w.model()->nbody - 1, 15);
}

TEST(SimCharacter, MjcfIsWrittenAndNamesEveryJoint) {
  std::filesystem::path p;
  MIMIC_REQUIRE_SHARED("deepmimic/characters/humanoid3d.txt", p);
  const std::string xml = build_mjcf(test::humanoid3d());
  for (const char* s : {"<freejoint name=\"root\"/>", "name=\"right_knee\" type=\"hinge\"", "name=\"chest\" type=\"ball\" damping=\"100\""})
    EXPECT_NE(xml.find(s), std::string::npos) << s;
}

TEST(SimWorld, SetStateReproducesClipKinematicsWithin1mm) {
  std::filesystem::path p;
  MIMIC_REQUIRE_SHARED("deepmimic/motions/humanoid3d_walk.txt", p);
  const CharacterModel ch = test::humanoid3d();
  const Clip walk = walk_clip(ch);
  World w(ch);
  for (int f = 0; f < walk.num_frames(); f += 5) {
    const Pose& pose = walk.frames[static_cast<std::size_t>(f)];
    w.set_state(pose);
    const LinkFrames sim = w.link_frames();
    const LinkFrames kin = forward_kinematics(ch.skeleton, pose);
    for (std::size_t j = 0; j < sim.joint_pos.size(); ++j) {
      EXPECT_LT((sim.joint_pos[j] - kin.joint_pos[j]).norm(), 1e-3) << ch.skeleton.joints[j].name;
      EXPECT_LT(rotation_distance(sim.joint_rot[j], kin.joint_rot[j]), 1e-6) << ch.skeleton.joints[j].name;
    }
  }
  // Mid-frame: state from the interpolated pose matches the interpolated kinematics.
  const Pose mid = walk.sample(0.5 / walk.fps);
  w.set_state(mid);
  EXPECT_LT((w.link_frames().joint_pos[5] - forward_kinematics(ch.skeleton, mid).joint_pos[5]).norm(), 1e-3);
  // Pose read back equals the pose set.
  w.set_state(walk.frames[7]);
  const Pose back = w.pose();
  for (std::size_t j = 0; j < back.rot.size(); ++j) EXPECT_LT(rotation_distance(back.rot[j], walk.frames[7].rot[j]), 1e-9);
  EXPECT_LT((w.root_position() - walk.frames[7].root_pos).norm(), 1e-12);
  // After physics steps too: the root alone reads as the full pose does.
  for (int i = 0; i < 5; ++i) w.step();
  EXPECT_EQ(w.root_position(), w.pose().root_pos);
  EXPECT_GT((w.root_position() - walk.frames[7].root_pos).norm(), 1e-4);
}

TEST(SimWorld, KinematicWalkKeepsFeetAtTheGround) {
  std::filesystem::path p;
  MIMIC_REQUIRE_SHARED("deepmimic/motions/humanoid3d_walk.txt", p);
  const CharacterModel ch = test::humanoid3d();
  const Clip walk = walk_clip(ch);
  World w(ch);
  double lowest = 1e9;
  for (const Pose& pose : walk.frames) {
    w.set_state(pose);
    lowest = std::min(lowest, geom_z_range(w, {"right_ankle", "left_ankle"}).first);
  }
  EXPECT_NEAR(lowest, 0.0, 0.03);  // the soles reach the floor, within 3 cm, at their lowest
}

class SimStand : public ::testing::TestWithParam<double> {};

// Zero actions: PD targets at every joint's rest rotation (upright, arms down). Started at the
// walk's first pose (one foot on the ground), the humanoid steps into double support and stands.
TEST_P(SimStand, ZeroActionsFromTheFirstPoseStandFor2Seconds) {
  std::filesystem::path p;
  MIMIC_REQUIRE_SHARED("deepmimic/motions/humanoid3d_walk.txt", p);
  const CharacterModel ch = test::humanoid3d();
  const Clip walk = walk_clip(ch);
  World w(ch, SimConfig{GetParam(), 30.0});
  w.set_state(walk.frames[0]);
  w.set_pd_targets(rest_pose(ch.skeleton));
  double lowest_root = 1e9, max_speed = 0;
  for (int k = 0; k < 60; ++k) {  // 2 s of control steps
    w.step();
    lowest_root = std::min(lowest_root, w.pose().root_pos.z());
    for (int i = 0; i < w.model()->nv; ++i) max_speed = std::max(max_speed, std::abs(w.data()->qvel[i]));
  }
  EXPECT_NEAR(w.time(), 2.0, 1e-9);
  EXPECT_GT(lowest_root, 0.8) << "fell";  // standing root height is 0.88 m
  EXPECT_LT(max_speed, 10.0) << "PD servos unstable";
  const std::vector<bool> contacts = w.ground_contacts();
  for (std::size_t j = 0; j < contacts.size(); ++j) {
    const std::string& n = ch.skeleton.joints[j].name;
    EXPECT_EQ(contacts[j], n == "right_ankle" || n == "left_ankle") << n;  // on its feet only
  }
}

// Targets at the walk's first pose: a statue in mid-stride topples (physics), but the servos
// hold every joint at its target throughout, without instability.
TEST_P(SimStand, ServosHoldAMidStridePoseStably) {
  std::filesystem::path p;
  MIMIC_REQUIRE_SHARED("deepmimic/motions/humanoid3d_walk.txt", p);
  const CharacterModel ch = test::humanoid3d();
  const Clip walk = walk_clip(ch);
  World w(ch, SimConfig{GetParam(), 30.0});
  w.set_state(walk.frames[0]);
  double worst = 0, max_speed = 0;
  for (int k = 0; k < 60; ++k) {
    w.step();
    const Pose now = w.pose();
    if (k < 30)  // the first second, before the body meets the floor
      for (std::size_t j = 1; j < now.rot.size(); ++j) worst = std::max(worst, rotation_distance(now.rot[j], walk.frames[0].rot[j]));
    for (int i = 0; i < w.model()->nv; ++i) max_speed = std::max(max_speed, std::abs(w.data()->qvel[i]));
  }
  EXPECT_LT(worst, 0.15);  // ~6 deg measured: the stance hip carries the body against kp = 500
  EXPECT_LT(max_speed, 20.0);  // the fall's impact included
  EXPECT_TRUE(w.pose().root_pos.allFinite());
}

INSTANTIATE_TEST_SUITE_P(Rates, SimStand, ::testing::Values(600.0, 1200.0));

// set_state starts the world afresh: a world that has fallen, with contacts, applied forces and a
// solver warm start behind it, then set to a state, steps to the same numbers, to the bit, as a new
// world set to that state (set_state clears what mj_resetData would, without clearing all of
// MuJoCo's buffer: sim/mujoco_state.hpp).
TEST(SimWorld, SetStateForgetsEverythingBeforeIt) {
  std::filesystem::path p;
  MIMIC_REQUIRE_SHARED("deepmimic/motions/humanoid3d_walk.txt", p);
  const CharacterModel ch = test::humanoid3d();
  const Clip walk = walk_clip(ch);
  World used(ch, SimConfig{600.0, 30.0});
  used.set_state(walk.frames[0]);
  for (int k = 0; k < 45; ++k) {  // a statue in mid-stride topples onto the floor, pushed
    used.data()->xfrc_applied[6 * 1 + 0] = 200.0;
    used.data()->qfrc_applied[7] = 30.0;
    used.step();
  }
  ASSERT_GT(used.data()->ncon, 2) << "lying on the floor";
  const PoseVelocity v = used.velocity();
  World fresh(ch, SimConfig{600.0, 30.0});
  for (World* w : {&used, &fresh}) {
    w->set_state(walk.frames[10], &v);
    w->set_pd_targets(walk.frames[20]);
  }
  const int nq = fresh.model()->nq, nv = fresh.model()->nv;
  for (int k = 0; k < 30; ++k) {
    for (World* w : {&used, &fresh}) w->step();
    for (int i = 0; i < nq; ++i) ASSERT_EQ(used.data()->qpos[i], fresh.data()->qpos[i]) << "qpos " << i << " at step " << k;
    for (int i = 0; i < nv; ++i) ASSERT_EQ(used.data()->qvel[i], fresh.data()->qvel[i]) << "qvel " << i << " at step " << k;
  }
  EXPECT_EQ(used.time(), fresh.time());
  EXPECT_GT(fresh.data()->ncon, 0) << "the steps compared had contacts to solve";
}

TEST(SimWorld, BadModelsAndRatesAreClearErrors) {
  const Clip one = [] {
    Clip c;
    c.skeleton.joints.push_back(Joint{"root", -1, JointType::Free, Vec3::Zero(), Quat::Identity(), Vec3::UnitZ(), {}, 0, false});
    return c;
  }();
  const CharacterModel ch = CharacterModel::from_skeleton(one.skeleton, "one_body");
  try {
    World w(ch, "<mujoco><worldbody><body name='root'><geom type='sphere'/></body></worldbody>", SimConfig{});
    FAIL() << "MuJoCo accepted a broken model";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("MuJoCo rejected the model of 'one_body'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(World(ch, SimConfig{600.0, 35.0}), Error);  // 600 / 35 is not whole
  World w(ch);
  Pose wrong;
  wrong.rot.assign(3, Quat::Identity());
  EXPECT_THROW(w.set_state(wrong), Error);
  const PoseVelocity no_joints;  // velocities must cover every joint too
  EXPECT_THROW(w.set_state(rest_pose(ch.skeleton), &no_joints), Error);
}

// Seed 000 built its CMU humanoid from a subject's segment lengths; so does from_skeleton.
TEST(SimCharacter, BodyGeneratedFromCmuSegmentLengths) {
  std::filesystem::path bvh;
  MIMIC_REQUIRE_SHARED("cmu-bvh/131_01.bvh", bvh);
  const Clip clip = load_bvh(bvh, AxisConvention{"y", "z", 0.056444});
  const CharacterModel ch = CharacterModel::from_skeleton(clip.skeleton, "cmu131", 60.0);
  EXPECT_NEAR(ch.total_mass(), 60.0, 1e-9);
  const auto body = [&](const char* n) { return ch.bodies[static_cast<std::size_t>(ch.skeleton.find(n))]; };
  const auto gain = [&](const char* n) { return ch.gains[static_cast<std::size_t>(ch.skeleton.find(n))].kp; };
  // Thigh capsule: along the LeftHip -> LeftKnee bone, shortened by its radius at both ends.
  const double thigh = ch.skeleton.joints[static_cast<std::size_t>(ch.skeleton.find("LeftKnee"))].offset.norm();
  EXPECT_EQ(body("LeftHip").shape, "capsule");
  EXPECT_NEAR(body("LeftHip").size.z(), thigh - 2 * 0.065, 1e-9);
  EXPECT_GT(body("LeftHip").mass, body("LeftKnee").mass);   // thigh heavier than shin
  EXPECT_GT(body("LeftKnee").mass, body("LeftToe").mass);   // shin heavier than toes
  EXPECT_GT(gain("LeftHip"), 5 * gain("LeftToe"));         // strong legs, weak toes
  EXPECT_GT(gain("lowerback"), gain("LeftWrist"));
  EXPECT_NEAR(ch.rest_height(), 1.42, 0.05);  // subject 131's rest pose, head top to toe bottom
  // It simulates: held at the clip's first pose, the servos keep every joint near its target.
  World w(ch);
  w.set_state(clip.frames[0]);
  double worst = 0;
  std::string worst_joint;
  for (int k = 0; k < 15; ++k) {
    w.step();
    const Pose now = w.pose();
    for (std::size_t j = 1; j < now.rot.size(); ++j) {
      const double d = rotation_distance(now.rot[j], clip.frames[0].rot[j]);
      if (d > worst) worst = d, worst_joint = ch.skeleton.joints[j].name;
    }
  }
  EXPECT_LT(worst, 0.3) << worst_joint;  // measured 0.22 at the stance ankle: frame 0 starts 2 cm into the floor
}

TEST(SimCharacter, DogMatchesItsFileAndTrotsOnTheFloor) {
  std::filesystem::path p;
  MIMIC_REQUIRE_SHARED("deepmimic/characters/dog3d.txt", p);
  const auto dir = test::shared_data() / "deepmimic";
  const CharacterModel dog = CharacterModel::from_deepmimic(dir / "characters/dog3d.txt", dir / "characters/dog3d_ctrl.txt");
  World w(dog);
  EXPECT_NEAR(mj_getTotalmass(w.model()), 29.25, 0.01 * 29.25);  // the file's body masses
  w.set_state(rest_pose(dog.skeleton, Vec3(0, 0, 1)));
  const auto [lo, hi] = geom_z_range(w);
  EXPECT_NEAR(hi - lo, dog.rest_height(), 0.01 * dog.rest_height());
  // Kinematic trot: the paws reach the floor (within 3 cm) and never sink below it by more.
  const Clip trot = load_deepmimic_motion(dir / "motions/dog3d_trot.txt", dog.skeleton);
  double lowest = 1e9;
  for (const Pose& pose : trot.frames) {
    w.set_state(pose);
    lowest = std::min(lowest, geom_z_range(w).first);
  }
  EXPECT_NEAR(lowest, 0.0, 0.03);
}

TEST(SimWorld, WritePosePlacesAGhostAsSetStateWouldAndLeavesTheWorldAlone) {
  std::filesystem::path p;
  MIMIC_REQUIRE_SHARED("deepmimic/motions/humanoid3d_walk.txt", p);
  const CharacterModel ch = test::humanoid3d();
  const Clip walk = walk_clip(ch);
  World w(ch);
  w.set_state(walk.frames[3]);
  const LinkFrames before = w.link_frames();
  mjData* ghost = mj_makeData(w.model());
  w.write_pose(walk.frames[20], ghost);
  World reference(ch);
  reference.set_state(walk.frames[20]);
  const mjData* d = reference.data();
  for (int b = 0; b < w.model()->nbody * 3; ++b) EXPECT_NEAR(ghost->xpos[b], d->xpos[b], 1e-9);
  mj_deleteData(ghost);
  const LinkFrames after = w.link_frames();
  for (std::size_t j = 0; j < before.joint_pos.size(); ++j) EXPECT_EQ(after.joint_pos[j], before.joint_pos[j]);
  EXPECT_THROW(w.write_pose(Pose{}, w.data()), Error);
}

namespace {

// A 1 kg forearm on a 1 t block in zero gravity, its joint (`type`: an elbow's hinge, or a ball as
// a shoulder's) a servo with DeepMimic's elbow gains (kp 300, kd 30, limit 60 N m) driven from rest
// towards `target` rad about y for a third of a second, one physics step per control step. The
// joint's angle after each step and its fastest speed.
std::pair<std::vector<double>, double> drive_joint(JointType type, PdLimit limit, double target) {
  Skeleton sk;
  sk.joints.push_back(Joint{"root", -1, JointType::Free, Vec3::Zero(), Quat::Identity(), Vec3::UnitZ(), {}, 0, false});
  sk.joints.push_back(Joint{"elbow", 0, type, Vec3::Zero(), Quat::Identity(), Vec3::UnitY(), {}, 60.0, false});
  sk.sites.push_back(Site{"hand", 1, Vec3(0.25, 0, 0)});
  CharacterModel ch = CharacterModel::from_skeleton(sk, "arm");
  ch.bodies[0].mass = 1000.0;
  ch.bodies[1].mass = 1.0;
  ch.gains[1] = PdGain{300.0, 30.0};
  World w(ch, SimConfig{600.0, 600.0, limit});
  w.model()->opt.gravity[2] = 0.0;
  w.set_state(rest_pose(ch.skeleton, Vec3(0, 0, 2)));
  Pose targets = rest_pose(ch.skeleton);
  targets.rot[1] = Quat(Eigen::AngleAxisd(target, Vec3::UnitY()));
  w.set_pd_targets(targets);
  const int dof = w.model()->jnt_dofadr[1], dofs = type == JointType::Spherical ? 3 : 1;
  std::vector<double> angles;
  double fastest = 0;
  for (int step = 0; step < 200; ++step) {
    w.step();
    angles.push_back(rotation_distance(Quat::Identity(), w.pose().rot[1]));
    fastest = std::max(fastest, Eigen::Map<const Eigen::VectorXd>(w.data()->qvel + dof, dofs).norm());
  }
  return {angles, fastest};
}

}  // namespace

// Under Spring the limit bounds the servo's spring alone and MuJoCo's damping (kd) grows with
// speed unbounded: driven hard, the joint settles where kd * speed = limit, 60 / 30 = 2 rad/s.
// Under Total (DeepMimic's rule) the limit bounds spring minus damping, so the joint speeds on
// until the spring-damper itself balances (kp err = kd speed + limit: over 10 rad/s at 1.5 rad
// to go). Below the limit the two are the same servo. Hinges and balls alike.
TEST(SimWorld, TorqueLimitBoundsTheSpringOrTheWholeServo) {
  for (const JointType type : {JointType::Revolute, JointType::Spherical}) {
    SCOPED_TRACE(type == JointType::Revolute ? "hinge" : "ball");
    const auto [spring_angles, spring_fastest] = drive_joint(type, PdLimit::Spring, 3.0);
    EXPECT_GT(spring_fastest, 1.95);
    EXPECT_LT(spring_fastest, 2.0 + 1e-6);
    const auto [total_angles, total_fastest] = drive_joint(type, PdLimit::Total, 3.0);
    EXPECT_GT(total_fastest, 10.0);
    EXPECT_LT(total_fastest, 30.0);  // kp * 3 rad = 900 = kd * 30 rad/s: the servo never pushes past
    EXPECT_GT(total_angles[59], 5.0 * spring_angles[59]);  // after 0.1 s: 1.7 rad against 0.2
    // 0.05 rad: the spring's 15 N m never reaches the limit.
    const auto [gentle_spring, a] = drive_joint(type, PdLimit::Spring, 0.05);
    const auto [gentle_total, b] = drive_joint(type, PdLimit::Total, 0.05);
    for (std::size_t i = 0; i < gentle_spring.size(); ++i) ASSERT_NEAR(gentle_spring[i], gentle_total[i], 1e-9) << "step " << i;
    EXPECT_NEAR(gentle_spring.back(), 0.05, 0.01);
  }
}

// The deepest point of the character inside the floor, from the contacts: the rest pose lowered
// so its lowest geom is 2 cm under the floor reads 0.02; raised 1 cm above it, 0.
TEST(SimWorld, GroundPenetrationIsHowDeepTheLowestGeomIsInTheFloor) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  World w(ch);
  Pose pose = rest_pose(ch.skeleton, Vec3(0, 0, 1.0));
  w.set_state(pose);
  const double lowest = geom_z_range(w).first;
  EXPECT_EQ(w.ground_penetration(), 0.0);  // 1 m up: no contact at all
  pose.root_pos.z() += -lowest - 0.02;
  w.set_state(pose);
  EXPECT_NEAR(geom_z_range(w).first, -0.02, 1e-9);
  EXPECT_NEAR(w.ground_penetration(), 0.02, 1e-6);
  pose.root_pos.z() += 0.03;
  w.set_state(pose);
  EXPECT_EQ(w.ground_penetration(), 0.0);
}

// Two spheres 1 m apart (radius 0.1 m; 2 kg at the root, 1 kg on a hinge about y), worked by hand:
// centre of mass 1/3 m from the root; the pair moving at 0.5 m/s along x and spinning at 1 rad/s
// about z has com velocity (0.5, 1/3, 0) and angular momentum about the com
//   2 (1/3)^2 + 1 (2/3)^2 + 2/5 (2 + 1) 0.1^2 = 2/3 + 0.012 kg m^2/s about z,
// the inertia about z and y; about x only the spheres' own 0.012. The hinge alone turning at
// 2 rad/s spins the small sphere about its own centre: 2/5 * 1 * 0.01 * 2 = 0.008 about y, the com still.
TEST(SimWorld, MomentumOfTwoSpheresIsTheHandWorkedOne) {
  Skeleton sk;
  sk.joints.push_back(Joint{"root", -1, JointType::Free, Vec3::Zero(), Quat::Identity(), Vec3::UnitZ(), {}, 0, false});
  sk.joints.push_back(Joint{"elbow", 0, JointType::Revolute, Vec3(1, 0, 0), Quat::Identity(), Vec3::UnitY(), {}, 60.0, false});
  CharacterModel ch = CharacterModel::from_skeleton(sk, "dumbbell");
  for (std::size_t j = 0; j < 2; ++j) {
    ch.bodies[j].shape = "sphere";
    ch.bodies[j].size = Vec3::Constant(0.2);
    ch.bodies[j].pos = Vec3::Zero();
    ch.bodies[j].rot = Quat::Identity();
  }
  ch.bodies[0].mass = 2.0;
  ch.bodies[1].mass = 1.0;
  const World w(ch);
  const Pose pose = rest_pose(ch.skeleton, Vec3(0, 0, 2));
  PoseVelocity v;
  v.joint_ang.assign(2, Vec3::Zero());
  v.root_lin = Vec3(0.5, 0, 0);
  v.root_ang = Vec3(0, 0, 1);
  const BodyMomentum m = w.momentum_of(pose, v);
  EXPECT_NEAR(m.mass, 3.0, 1e-12);
  EXPECT_LT((m.com - Vec3(1.0 / 3, 0, 2)).norm(), 1e-9);
  EXPECT_LT((m.com_velocity - Vec3(0.5, 1.0 / 3, 0)).norm(), 1e-9);
  EXPECT_LT((m.angular - Vec3(0, 0, 2.0 / 3 + 0.012)).norm(), 1e-9);
  const Eigen::Matrix3d inertia = Eigen::Vector3d(0.012, 2.0 / 3 + 0.012, 2.0 / 3 + 0.012).asDiagonal();
  EXPECT_LT((m.inertia - inertia).norm(), 1e-9) << m.inertia;
  v.root_lin = v.root_ang = Vec3::Zero();
  v.joint_ang[1] = Vec3(0, 2, 0);
  const BodyMomentum hinge = w.momentum_of(pose, v);
  EXPECT_LT(hinge.com_velocity.norm(), 1e-12);
  EXPECT_LT((hinge.angular - Vec3(0, 0.008, 0)).norm(), 1e-9);
  EXPECT_LT(w.velocity().root_lin.norm(), 1e-12);  // the world's own state: still at rest
  EXPECT_THROW((void)w.momentum_of(Pose{}, v), Error);
}

// A foot without a toe joint stands on a sole box: 1.25 radii behind the ankle to 2.75 ahead of
// its sole site, 2.25 radii wide, 1.25 thick, its bottom at the site (the built-in humanoid's
// ankle radius is 4 cm, its sole 6 cm below and 4 cm ahead of the ankle). Standing, each sole
// touches the floor at its four corners, a support an ankle torque can push against (a capsule's
// end touches at one point); a foot with a toe joint keeps its capsule.
TEST(SimCharacter, AFootWithoutToesStandsOnASoleBox) {
  const CharacterModel ch = CharacterModel::from_skeleton(builtin_humanoid(), "builtin");
  const BodyDef& foot = ch.bodies[static_cast<std::size_t>(ch.skeleton.find("left_ankle"))];
  EXPECT_EQ(foot.shape, "box");
  EXPECT_NEAR(foot.size.x(), 0.05 + 0.04 + 0.11, 1e-12);
  EXPECT_NEAR(foot.size.y(), 0.09, 1e-12);
  EXPECT_NEAR(foot.size.z(), 0.05, 1e-12);
  EXPECT_NEAR(foot.pos.x(), (-0.05 + 0.15) / 2, 1e-12);
  EXPECT_NEAR(foot.pos.z() - foot.size.z() / 2, -0.06, 1e-12);
  World w(ch);
  w.set_state(rest_pose(ch.skeleton, Vec3(0, 0, ch.rest_root_height())));
  w.set_pd_targets(rest_pose(ch.skeleton));
  w.step();
  const int left_foot = mj_name2id(w.model(), mjOBJ_BODY, "left_ankle");
  int corners = 0;
  for (int c = 0; c < w.data()->ncon; ++c) {
    const mjContact& con = w.data()->contact[c];
    if (w.model()->geom_bodyid[con.geom1] == left_foot || w.model()->geom_bodyid[con.geom2] == left_foot) ++corners;
  }
  EXPECT_EQ(corners, 4);
  // CMU's feet have toes: their capsules stay.
  std::filesystem::path bvh;
  MIMIC_REQUIRE_SHARED("cmu-bvh/131_01.bvh", bvh);
  const CharacterModel cmu = CharacterModel::from_skeleton(load_bvh(bvh, AxisConvention{"y", "z", 0.056444}).skeleton, "cmu131", 60.0);
  EXPECT_EQ(cmu.bodies[static_cast<std::size_t>(cmu.skeleton.find("LeftAnkle"))].shape, "capsule");
}

// The demo's squat: a 2 s loop from standing to a shallow squat (knees bent 1 rad at 1 s) and
// back, the soles on the floor at every frame.
TEST(SimCharacter, TheBuiltInSquatKeepsItsSolesOnTheFloor) {
  const Clip squat = builtin_squat();
  EXPECT_EQ(squat.loop, LoopMode::Wrap);
  EXPECT_NEAR(squat.duration(), 2.0, 1e-9);
  const Skeleton& sk = squat.skeleton;
  const int knee = sk.find("left_knee");
  EXPECT_NEAR(revolute_angle(sk.joints[static_cast<std::size_t>(knee)], squat.sample(1.0).rot[static_cast<std::size_t>(knee)]), -1.0, 1e-6);
  double lowest_root = 1e9, highest_root = 0;
  for (const Pose& p : squat.frames) {
    Clip one = squat;
    one.frames = {p};
    EXPECT_NEAR(clip_min_height(one), 0.0, 1e-9);
    const LinkFrames links = forward_kinematics(sk, p);
    for (const char* sole : {"left_sole", "right_sole"})
      EXPECT_NEAR(links.site_pos[static_cast<std::size_t>(sk.find_site(sole))].z(), 0.0, 0.01) << sole;
    lowest_root = std::min(lowest_root, p.root_pos.z());
    highest_root = std::max(highest_root, p.root_pos.z());
  }
  EXPECT_GT(highest_root - lowest_root, 0.1);  // it goes down
}
