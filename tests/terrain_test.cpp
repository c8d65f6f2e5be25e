// Terrain kinds against MuJoCo (ray casts onto the compiled model) and by hand, and the
// "height_map" observation in the heading frame. Uses the built-in humanoid: no shared data.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "core/error.hpp"
#include "core/math.hpp"
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

TerrainSpec spec_of(TerrainKind kind) {
  TerrainSpec s;
  s.kind = kind;
  s.seed = 7;
  return s;
}

// A compiled World standing on `terrain`, its character lifted far above the ground so that
// rays from z = 20 only meet the terrain.
std::unique_ptr<World> world_on(const Terrain& terrain) {
  MjcfOptions opts;
  terrain.add_to(opts);
  auto w = std::make_unique<World>(builtin(), SimConfig{}, opts);
  terrain.install(w->model());
  w->set_state(rest_pose(builtin().skeleton, Vec3(0, 0, 50)));
  return w;
}

// Height of the first surface below (x, y, 20) according to MuJoCo, or NaN if none.
double ray_height(const World& w, double x, double y) {
  const mjtNum from[3] = {x, y, 20.0}, down[3] = {0, 0, -1};
  int geom = -1;
  const mjtNum dist = mj_ray(w.model(), w.data(), from, down, nullptr, 1, -1, &geom);
  return dist < 0 ? std::nan("") : 20.0 - dist;
}

}  // namespace

TEST(Terrain, KindNamesRoundTrip) {
  for (TerrainKind k : {TerrainKind::Flat, TerrainKind::Slope, TerrainKind::Gaps, TerrainKind::Stairs, TerrainKind::HeightField, TerrainKind::Walls})
    EXPECT_EQ(terrain_kind_from_string(to_string(k)), k);
  EXPECT_THROW(terrain_kind_from_string("lava"), Error);
}

TEST(Terrain, EveryKindMatchesMuJoCoRayCasts) {
  for (TerrainKind kind : {TerrainKind::Flat, TerrainKind::Slope, TerrainKind::Gaps, TerrainKind::Stairs, TerrainKind::HeightField,
                           TerrainKind::Walls}) {
    TerrainSpec s = spec_of(kind);
    s.slope_segments = kind == TerrainKind::Slope ? 3 : 1;  // random up and down inclines
    const Terrain terrain(s);
    const auto w = world_on(terrain);
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> ux(-s.behind - 2, s.ahead + 2), uy(-s.width / 2 - 2, s.width / 2 + 2);
    double worst = 0;
    for (int i = 0; i < 400; ++i) {
      const double x = i < 40 ? 0.05 * i - 1.0 : ux(rng), y = i < 40 ? 0.3 : uy(rng);  // the start zone, then anywhere
      const double ray = ray_height(*w, x, y);
      ASSERT_FALSE(std::isnan(ray)) << to_string(kind) << " at " << x << ", " << y;
      worst = std::max(worst, std::abs(ray - terrain.height(x, y)));
      if (i < 40) {
        EXPECT_NEAR(terrain.height(x, y), 0.0, 1e-6) << to_string(kind) << ": the start zone is flat";  // float samples
      }
    }
    EXPECT_LT(worst, 1e-3) << to_string(kind);
  }
}

TEST(Terrain, SlopeHeightIsDistanceTimesTangent) {
  TerrainSpec s = spec_of(TerrainKind::Slope);
  s.slope_deg = 12.0;
  const Terrain up(s);
  const double t = std::tan(deg_to_rad(12.0));
  EXPECT_NEAR(up.height(1.5, 3.0), 0.0, 1e-9);                       // before the incline
  EXPECT_NEAR(up.height(7.0, -4.0), (7.0 - s.start_zone) * t, 1e-6);  // on it
  EXPECT_NEAR(up.height(30.0, 0.0), s.slope_length * t, 1e-6);        // the plateau
  s.slope_deg = -8.0;
  const Terrain down(s);
  EXPECT_NEAR(down.height(5.0, 1.0), -3.0 * std::tan(deg_to_rad(8.0)), 1e-6);
  EXPECT_NEAR(down.base_height(), -s.slope_length * std::tan(deg_to_rad(8.0)), 1e-6);
  // MuJoCo agrees at the same place.
  EXPECT_NEAR(ray_height(*world_on(up), 7.0, -4.0), (7.0 - s.start_zone) * t, 1e-3);
}

TEST(Terrain, GapIsAHole) {
  const TerrainSpec s = spec_of(TerrainKind::Gaps);
  const Terrain gaps(s);
  const auto w = world_on(gaps);
  const double gap = s.start_zone + s.gap_width / 2;                    // the middle of the first gap
  const double platform = s.start_zone + s.gap_width + s.gap_spacing / 2;
  for (double y : {-3.0, 0.0, 4.0}) {
    EXPECT_NEAR(ray_height(*w, gap, y), -s.gap_depth, 1e-6);  // the floor far below
    EXPECT_NEAR(ray_height(*w, platform, y), 0.0, 1e-6);
    EXPECT_NEAR(gaps.height(gap, y), -s.gap_depth, 1e-12);
  }
  // The second gap begins one gap and one platform later.
  EXPECT_NEAR(ray_height(*w, gap + s.gap_width + s.gap_spacing, 0.0), -s.gap_depth, 1e-6);
}

TEST(Terrain, StairsRiseByStepHeightPerStepDepth) {
  const TerrainSpec s = spec_of(TerrainKind::Stairs);
  const Terrain stairs(s);
  const auto w = world_on(stairs);
  for (int k = 0; k < s.step_count; ++k) {
    const double x = s.start_zone + (k + 0.5) * s.step_depth;  // middle of step k
    EXPECT_NEAR(stairs.height(x, 0.0), (k + 1) * s.step_height, 1e-12) << "step " << k;
    EXPECT_NEAR(ray_height(*w, x, 1.0), (k + 1) * s.step_height, 1e-6) << "step " << k;
  }
  // The landing, then down again to the ground.
  const double top = s.start_zone + s.step_count * s.step_depth;
  EXPECT_NEAR(ray_height(*w, top + s.landing / 2, 0.0), s.step_count * s.step_height, 1e-6);
  EXPECT_NEAR(ray_height(*w, top + s.landing + 0.5 * s.step_depth, 0.0), (s.step_count - 1) * s.step_height, 1e-6);
  EXPECT_NEAR(ray_height(*w, top + s.landing + s.step_count * s.step_depth + 0.5, 0.0), 0.0, 1e-6);
}

TEST(Terrain, CourseEndIsWhereTheLastFeatureEnds) {
  // Defaults by hand: stairs 2 + (8 up + 7 down) x 0.3 + a 2 m landing; gaps 2 + 10 x 0.5 + 9 x 2;
  // walls 2 + 4 x 7 + 0.3; one 10 m slope from 2; a height field's bumps run to `ahead` (40).
  EXPECT_NEAR(Terrain(spec_of(TerrainKind::Stairs)).course_end(), 8.5, 1e-12);
  EXPECT_NEAR(Terrain(spec_of(TerrainKind::Gaps)).course_end(), 25.0, 1e-12);
  EXPECT_NEAR(Terrain(spec_of(TerrainKind::Walls)).course_end(), 30.3, 1e-12);
  EXPECT_NEAR(Terrain(spec_of(TerrainKind::Slope)).course_end(), 12.0, 1e-12);
  EXPECT_NEAR(Terrain(spec_of(TerrainKind::HeightField)).course_end(), 40.0, 1e-12);
  // The ground just before the end is the last feature; just after, the flat ground beyond.
  const Terrain stairs(spec_of(TerrainKind::Stairs));
  EXPECT_NEAR(stairs.height(8.45, 0.0), 0.15, 1e-12);
  EXPECT_NEAR(stairs.height(8.55, 0.0), 0.0, 1e-12);
  const Terrain gaps(spec_of(TerrainKind::Gaps));
  EXPECT_NEAR(gaps.height(24.95, 0.0), -2.0, 1e-12);
  EXPECT_NEAR(gaps.height(25.05, 0.0), 0.0, 1e-12);
  EXPECT_THROW((void)Terrain(spec_of(TerrainKind::Flat)).course_end(), Error);
}

TEST(Terrain, EachWallBlocksTheCourseButForOneOpeningDrawnFromTheSeed) {
  const TerrainSpec s = spec_of(TerrainKind::Walls);  // 5 walls 1 m high, 0.3 m thick, every 7 m from x = 2, 20 m wide
  const Terrain walls(s);
  const auto w = world_on(walls);
  std::vector<double> openings;
  for (int k = 0; k < s.wall_count; ++k) {
    const double x = s.start_zone + k * s.wall_spacing + s.wall_thickness / 2;  // inside wall k
    // Across the course at 5 cm steps: wall everywhere but one stretch of opening_width at ground height.
    std::vector<double> open;
    for (int i = 0; i < static_cast<int>(std::lround(s.width / 0.05)); ++i) {
      const double y = -s.width / 2 + 0.025 + 0.05 * i;
      const double h = walls.height(x, y);
      ASSERT_TRUE(h == 0.0 || h == s.wall_height) << "wall " << k << " at y " << y << ": " << h;
      EXPECT_NEAR(ray_height(*w, x, y), h, 1e-6) << "wall " << k << " at y " << y;
      if (h == 0.0) open.push_back(y);
    }
    ASSERT_FALSE(open.empty()) << "wall " << k << " has no opening";
    for (std::size_t i = 1; i < open.size(); ++i) ASSERT_NEAR(open[i] - open[i - 1], 0.05, 1e-9) << "wall " << k << " has two openings";
    EXPECT_NEAR(open.back() - open.front() + 0.05, s.opening_width, 0.051) << "wall " << k;
    openings.push_back((open.front() + open.back()) / 2);
    // Between the walls the ground is flat.
    EXPECT_EQ(walls.height(x + s.wall_spacing / 2, 0.0), 0.0);
  }
  // The openings are placed by the seed: not all in one place, the same again for the seed.
  EXPECT_GT(*std::max_element(openings.begin(), openings.end()) - *std::min_element(openings.begin(), openings.end()), 1.0);
  const Terrain again(s);
  for (int k = 0; k < s.wall_count; ++k)
    EXPECT_EQ(again.height(s.start_zone + k * s.wall_spacing + 0.1, openings[static_cast<std::size_t>(k)]), 0.0);
  EXPECT_EQ(walls.height(1.0, 0.0), 0.0);  // the start zone
}

TEST(Terrain, AWallsCourseRedrawnMovesItsOpeningsInTheModelToo) {
  const TerrainSpec s = spec_of(TerrainKind::Walls);
  Terrain walls(s);
  const auto w = world_on(walls);
  const auto wall_x = [&](int k) { return s.start_zone + k * s.wall_spacing + s.wall_thickness / 2; };
  // The middle of wall k's opening, from height() at 5 cm steps across the course.
  const auto opening = [&](int k) {
    double sum = 0;
    int n = 0;
    for (int i = 0; i < static_cast<int>(std::lround(s.width / 0.05)); ++i) {
      const double y = -s.width / 2 + 0.025 + 0.05 * i;
      if (walls.height(wall_x(k), y) == 0.0) sum += y, ++n;
    }
    return n ? sum / n : std::nan("");
  };
  std::vector<double> before;
  for (int k = 0; k < s.wall_count; ++k) before.push_back(opening(k));
  walls.redraw(99, w->model());
  mj_forward(w->model(), w->data());
  int moved = 0;
  for (int k = 0; k < s.wall_count; ++k) {
    if (std::abs(opening(k) - before[static_cast<std::size_t>(k)]) > 0.5) ++moved;
    for (int i = 0; i < static_cast<int>(std::lround(s.width / 0.05)); ++i) {  // MuJoCo's walls are where height() says
      const double y = -s.width / 2 + 0.025 + 0.05 * i;
      ASSERT_NEAR(ray_height(*w, wall_x(k), y), walls.height(wall_x(k), y), 1e-6) << "wall " << k << " at y " << y;
    }
  }
  EXPECT_GE(moved, 3);  // of 5: a new course
  // The course of seed 99 built fresh is the one redrawn.
  TerrainSpec again = s;
  again.seed = 99;
  const Terrain fresh(again);
  for (int k = 0; k < s.wall_count; ++k) EXPECT_EQ(fresh.height(wall_x(k), opening(k)), 0.0);
  // Only walls are redrawn.
  Terrain stairs(spec_of(TerrainKind::Stairs));
  EXPECT_THROW(stairs.redraw(1, w->model()), Error);
  TerrainSpec redrawn_stairs = spec_of(TerrainKind::Stairs);
  redrawn_stairs.redraw = true;
  EXPECT_THROW(Terrain{redrawn_stairs}, Error);
}

TEST(Terrain, ACurriculumLevelScalesTheCourseInTheModelToo) {
  // Level k of 4 scales each kind's difficulty by k/4: stairs' steps, gaps' width, slopes' angle,
  // bumps' height; MuJoCo's ground follows height() at every level.
  for (TerrainKind kind : {TerrainKind::Stairs, TerrainKind::Gaps, TerrainKind::Slope, TerrainKind::HeightField}) {
    TerrainSpec s = spec_of(kind);
    s.levels = 4;
    Terrain terrain(s);
    EXPECT_EQ(terrain.level(), 4) << to_string(kind);  // built at the top level
    const auto w = world_on(terrain);
    terrain.set_level(1, w->model());
    mj_forward(w->model(), w->data());
    EXPECT_EQ(terrain.level(), 1);
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> ux(-s.behind - 2, s.ahead + 2), uy(-s.width / 2 - 2, s.width / 2 + 2);
    double worst = 0;
    for (int i = 0; i < 300; ++i) {
      const double x = ux(rng), y = uy(rng);
      worst = std::max(worst, std::abs(ray_height(*w, x, y) - terrain.height(x, y)));
    }
    EXPECT_LT(worst, 1e-3) << to_string(kind) << " at level 1";
    switch (kind) {
      case TerrainKind::Stairs:  // 0.15 m steps at the top: 0.0375 m at level 1
        EXPECT_NEAR(terrain.height(s.start_zone + 2.5 * s.step_depth, 0), 3 * 0.0375, 1e-12);
        EXPECT_NEAR(terrain.spec().step_height, 0.0375, 1e-12);
        break;
      case TerrainKind::Gaps:  // 0.5 m gaps: 0.125 m, so the first platform begins at 2.125 m
        EXPECT_EQ(terrain.height(s.start_zone + 0.1, 0), terrain.base_height());
        EXPECT_EQ(terrain.height(s.start_zone + 0.13, 0), 0.0);
        EXPECT_NEAR(terrain.course_end(), s.start_zone + 10 * 0.125 + 9 * s.gap_spacing, 1e-12);
        break;
      case TerrainKind::Slope:  // 10 degrees: 2.5
        EXPECT_NEAR(terrain.height(s.start_zone + 4.0, 0), 4.0 * std::tan(deg_to_rad(2.5)), 1e-5);
        break;
      default: {  // bumps a quarter as high as the same seed's top level
        const Terrain top(spec_of(kind));
        for (double x : {3.3, 7.1, 15.4}) EXPECT_NEAR(terrain.height(x, 1.2), top.height(x, 1.2) / 4, 1e-5);
      }
    }
    terrain.set_level(4, w->model());  // back to the course as given
    const Terrain given(spec_of(kind));
    for (double x : {2.2, 3.05, 6.6, 12.0}) EXPECT_NEAR(terrain.height(x, 0.4), given.height(x, 0.4), 1e-9) << to_string(kind);
    EXPECT_THROW(terrain.set_level(0, w->model()), Error);
    EXPECT_THROW(terrain.set_level(5, w->model()), Error);
  }
  // Walls and flat ground have no curriculum; a course without levels takes none.
  TerrainSpec walls = spec_of(TerrainKind::Walls);
  walls.levels = 3;
  EXPECT_THROW(Terrain{walls}, Error);
  Terrain plain(spec_of(TerrainKind::Stairs));
  const auto w = world_on(plain);
  EXPECT_EQ(plain.level(), 0);
  EXPECT_THROW(plain.set_level(1, w->model()), Error);
}

TEST(Terrain, HeightFieldIsBumpyAndDeterministicForASeed) {
  const TerrainSpec s = spec_of(TerrainKind::HeightField);
  const Terrain a(s), b(s);
  TerrainSpec other = s;
  other.seed = 8;
  const Terrain c(other);
  double sum = 0, sum2 = 0, differ = 0;
  int n = 0;
  for (double x = 3.05; x < 20; x += 0.37) {
    for (double y = -8.05; y < 8; y += 0.41, ++n) {
      const double h = a.height(x, y);
      EXPECT_EQ(h, b.height(x, y));
      EXPECT_GE(h, 0.0);
      EXPECT_LE(h, s.roughness + 1e-9);
      differ = std::max(differ, std::abs(h - c.height(x, y)));
      sum += h, sum2 += h * h;
    }
  }
  const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
  EXPECT_GT(sd, 0.1 * s.roughness);  // not flat
  EXPECT_GT(differ, 0.3 * s.roughness);  // another seed, other bumps
}

TEST(Terrain, RejectsBadSpecs) {
  auto bad = [](auto edit) {
    TerrainSpec s;
    edit(s);
    return s;
  };
  EXPECT_THROW(Terrain(bad([](TerrainSpec& s) { s.kind = TerrainKind::Slope, s.slope_deg = 75; })), Error);
  EXPECT_THROW(Terrain(bad([](TerrainSpec& s) { s.kind = TerrainKind::Gaps, s.gap_count = 100; })), Error);
  EXPECT_THROW(Terrain(bad([](TerrainSpec& s) { s.kind = TerrainKind::Stairs, s.step_height = 0; })), Error);
  EXPECT_THROW(Terrain(bad([](TerrainSpec& s) { s.kind = TerrainKind::HeightField, s.roughness = -1; })), Error);
  EXPECT_THROW(Terrain(bad([](TerrainSpec& s) { s.width = 0; })), Error);
  EXPECT_THROW(Terrain(bad([](TerrainSpec& s) { s.kind = TerrainKind::Walls, s.opening_width = 25; })), Error);
  EXPECT_THROW(Terrain(bad([](TerrainSpec& s) { s.kind = TerrainKind::Walls, s.wall_count = 10; })), Error);
  // A model built without the terrain's height field cannot take its data.
  const Terrain hf(spec_of(TerrainKind::HeightField));
  World plain(builtin());
  EXPECT_THROW(hf.install(plain.model()), Error);
}

TEST(TerrainEnv, CharacterStartsStandingOnEveryKind) {
  // DeepMimic's humanoid stands with zero actions; on every kind it starts on flat ground.
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  for (TerrainKind kind : {TerrainKind::Slope, TerrainKind::Gaps, TerrainKind::Stairs, TerrainKind::HeightField, TerrainKind::Walls}) {
    CharacterEnvConfig cfg;
    cfg.terrain = spec_of(kind);
    CharacterEnv env(ch, cfg);
    std::mt19937_64 rng(1);
    env.reset(rng);
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(env.action_size());
    for (int i = 0; i < 60; ++i) ASSERT_FALSE(env.step(zero).done()) << to_string(kind);
    EXPECT_GT(env.world().pose().root_pos.z(), 0.95 * ch.rest_root_height()) << to_string(kind);
  }
}

TEST(TerrainEnv, HeightMapIsTheTerrainAroundTheCharacterInItsHeadingFrame) {
  CharacterEnvConfig cfg;
  cfg.terrain = spec_of(TerrainKind::HeightField);
  cfg.observations.names = {"height_map"};
  cfg.observations.height_map_size = 7;
  cfg.observations.height_map_spacing = 0.3;
  cfg.observations.height_map_ahead = 0.5;
  CharacterEnv env(builtin(), cfg);
  ASSERT_EQ(env.observation_size(), 49);
  const Terrain& t = env.terrain();
  const Vec3 root(6.2, -2.7, 1.4);
  InitState s{rest_pose(builtin().skeleton, root), PoseVelocity{}, 0.0, {}};
  s.velocity.joint_ang.assign(builtin().skeleton.joints.size(), Vec3::Zero());
  const Eigen::VectorXd facing_x = env.reset(s);
  s.pose.rot[0] = axis_rotation('z', kPi / 2);  // turned left: facing +y
  const Eigen::VectorXd facing_y = env.reset(s);
  for (int i = 0; i < 7; ++i) {
    for (int j = 0; j < 7; ++j) {
      const double ahead = 0.5 + (i - 3) * 0.3, left = (j - 3) * 0.3;
      // Facing +x: ahead is +x, left is +y. Facing +y: ahead is +y, left is -x.
      EXPECT_NEAR(facing_x[i * 7 + j], t.height(root.x() + ahead, root.y() + left) - root.z(), 1e-9);
      EXPECT_NEAR(facing_y[i * 7 + j], t.height(root.x() - left, root.y() + ahead) - root.z(), 1e-9);
    }
  }
  EXPECT_GT((facing_x - facing_y).cwiseAbs().maxCoeff(), 0.02);  // the bumps differ by direction
}

TEST(TerrainEnv, ACurriculumGoesUpAfterACrossingAndDownAfterAnEarlyFall) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  CharacterEnvConfig cfg;
  cfg.terrain = spec_of(TerrainKind::Stairs);
  cfg.terrain.levels = 3;
  CharacterEnv env(ch, cfg);
  EXPECT_EQ(env.terrain_level(), 1);  // every environment starts at the lowest level
  EXPECT_NEAR(env.terrain().spec().step_height, 0.05, 1e-12);
  const double end = env.terrain().course_end();
  const auto standing_at = [&](double x) {
    InitState s{rest_pose(ch.skeleton, Vec3(x, 0, 1.0)), PoseVelocity{}, 0.0, {}};
    s.velocity.joint_ang.assign(ch.skeleton.joints.size(), Vec3::Zero());
    return s;
  };
  InitState lying = standing_at(0.0);  // face down at the start: a fall at the first step
  lying.pose.root_pos.z() = 0.1;
  lying.pose.rot[0] = axis_rotation('y', kPi / 2);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(env.action_size());
  // An episode whose root got 0.5 m past the course's end: a level up at the next start.
  env.reset(standing_at(end + 0.6));
  StepResult r = env.step(zero);
  ASSERT_EQ(r.info.size(), 1u);
  EXPECT_EQ(r.info[0].first, "terrain_level");
  EXPECT_EQ(r.info[0].second, 1.0);
  env.reset(standing_at(0.0));
  EXPECT_EQ(env.terrain_level(), 2);
  EXPECT_NEAR(env.terrain().spec().step_height, 0.10, 1e-12);
  EXPECT_EQ(env.step(zero).info[0].second, 2.0);
  // Short of the margin, without a fall: the level stays (an episode standing 0.4 m past the end).
  env.reset(standing_at(end + 0.4));
  env.step(zero);
  env.reset(standing_at(end + 0.7));
  EXPECT_EQ(env.terrain_level(), 2);
  env.reset(lying);  // after the episode that stood 0.7 m past it

  EXPECT_EQ(env.terrain_level(), 3);
  EXPECT_NEAR(env.terrain().height(cfg.terrain.start_zone + 0.1, 0), 0.15, 1e-12);
  // A fall before the course's middle: a level down; the top is not passed, the lowest level kept.
  ASSERT_EQ(env.step(zero).termination, Termination::Fall);
  env.reset(lying);
  EXPECT_EQ(env.terrain_level(), 2);
  env.step(zero);
  env.reset(lying);
  env.step(zero);
  env.reset(lying);
  EXPECT_EQ(env.terrain_level(), 1);
  // Without levels the env reports nothing.
  CharacterEnvConfig plain;
  plain.terrain = spec_of(TerrainKind::Stairs);
  CharacterEnv flat_rule(ch, plain);
  flat_rule.reset(standing_at(0.0));
  EXPECT_TRUE(flat_rule.step(zero).info.empty());
  EXPECT_EQ(flat_rule.terrain_level(), 0);
}
