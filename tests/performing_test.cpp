// Robustness with recovery (control/performing): the fraction of the time a skill performs in a
// play session under the projectile test, without and with skills that take a fallen character.
#include <gtest/gtest.h>

#include "control/performing.hpp"
#include "error_message.hpp"
#include "mimic/runtime.hpp"
#include "test_data.hpp"

using namespace mimic;
using test::error_of;

namespace {

const std::filesystem::path kModels = std::filesystem::path(MIMIC_SOURCE_DIR) / "models";

TEST(PerformingReport, MeansAndPopulationSpreadOverTheTrials) {
  PerformingReport r;
  r.fractions = {1.0, 0.5};
  r.downs = {0, 3};
  r.recoveries = {0, 1};
  EXPECT_DOUBLE_EQ(r.mean(), 0.75);
  EXPECT_DOUBLE_EQ(r.std(), 0.25);
  EXPECT_DOUBLE_EQ(r.mean_downs(), 1.5);
  EXPECT_DOUBLE_EQ(r.mean_recoveries(), 0.5);
  EXPECT_NE(error_of([] { (void)measure_performing({}, PerformingOptions{}); }).find("give the skill that performs"), std::string::npos);
}

TEST(Performing, TheWalkPerformsThroughoutWithoutCubesAndLessUnderHeavyOnesAndAGetUpsTimeIsNotPerforming) {
  std::filesystem::path data;
  MIMIC_REQUIRE_SHARED("deepmimic/characters/humanoid3d.txt", data);
  PerformingOptions o;
  o.seconds = 2.0;
  o.trials = 2;
  const auto walk = Skill::load(kModels / "humanoid_walk_iccgan", "walk");
  const PerformingReport calm = measure_performing({walk}, o);
  EXPECT_EQ(calm.seconds, 2.0);
  EXPECT_EQ(calm.fractions, (std::vector<double>{1.0, 1.0}));
  EXPECT_EQ(calm.downs, (std::vector<int>{0, 0}));
  EXPECT_EQ(calm.recoveries, (std::vector<int>{0, 0}));

  // 60 kg cubes every frame floor the walk within 4 s (seed 004's test: at 30 kg it lasts 2-3 s).
  const std::vector<std::string> cubes = {"env.projectiles={enabled: true, mass: 60}", "env.max_seconds=5"};
  const auto pelted = Skill::load(kModels / "humanoid_walk_iccgan", "walk", cubes);
  o.seconds = 4.0;
  o.trials = 1;
  const PerformingReport without = measure_performing({pelted}, o);
  ASSERT_GE(without.downs.at(0), 1);
  EXPECT_LT(without.fractions.at(0), 1.0);
  EXPECT_EQ(without.recoveries.at(0), 0);
  // The run as the "get-up": it takes the fallen character at once and cannot hand it back (the
  // walk's score of a lying character is low), so nothing after the fall counts.
  const auto run = Skill::load(kModels / "humanoid_run_iccgan_straight_loop", "run", cubes);
  const PerformingReport with = measure_performing({pelted, run}, o);
  EXPECT_GE(with.downs.at(0), 1);
  EXPECT_LE(with.fractions.at(0), without.fractions.at(0) + 1e-12);
  EXPECT_EQ(with.recoveries.at(0), 0);

  o.seconds = 0;
  EXPECT_NE(error_of([&] { (void)measure_performing({walk}, o); }).find("seconds must be positive"), std::string::npos);
}

}  // namespace
