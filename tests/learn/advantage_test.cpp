// GAE(lambda) and TD(lambda) targets against values computed by hand.
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "learn/ppo/advantage.hpp"

using namespace mimic;

TEST(Advantages, MatchHandComputedValuesAcrossTruncationAndFailure) {
  // gamma 0.9, lambda 0.8 (gamma * lambda = 0.72). Two episodes of one environment:
  //  s0 -> s1 ends by a time limit (bootstrapped with V(last obs) = 2.0),
  //  s2 -> s3 ends by a fall (its next value, 0.3, must be ignored).
  const std::vector<AdvantageStep> steps = {
      {1.0, 0.5, 0.6, false, false},
      {0.0, 0.6, 2.0, true, false},
      {2.0, 1.0, 0.7, false, false},
      {1.0, 0.7, 0.3, true, true},
  };
  const Advantages a = compute_advantages(steps, 0.9, 0.8);
  // s3: delta = 1 - 0.7 = 0.3.  s2: delta = 2 + 0.9*0.7 - 1 = 1.63, A = 1.63 + 0.72*0.3 = 1.846.
  // s1: delta = 0.9*2.0 - 0.6 = 1.2 (nothing flows back from s2).  s0: 1.04 + 0.72*1.2 = 1.904.
  const std::vector<double> adv = {1.904, 1.2, 1.846, 0.3};
  const std::vector<double> target = {2.404, 1.8, 2.846, 1.0};
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(a.advantage[i], adv[i], 1e-12) << i;
    EXPECT_NEAR(a.target[i], target[i], 1e-12) << i;
  }
}

TEST(Advantages, LambdaOneIsTheDiscountedReturnAndZeroIsOneStepTd) {
  // Three steps, then a bootstrap value of 4 after the last (horizon end, not an episode end).
  const std::vector<AdvantageStep> steps = {{1, 0.2, 0.3, false, false}, {2, 0.3, 0.1, false, false}, {3, 0.1, 4.0, false, false}};
  const Advantages mc = compute_advantages(steps, 0.5, 1.0);
  // Return from s0: 1 + 0.5*2 + 0.25*3 + 0.125*4 = 3.25; from s1: 2 + 1.5 + 1 = 4.5; s2: 3 + 2 = 5.
  EXPECT_NEAR(mc.target[0], 3.25, 1e-12);
  EXPECT_NEAR(mc.target[1], 4.5, 1e-12);
  EXPECT_NEAR(mc.target[2], 5.0, 1e-12);
  EXPECT_NEAR(mc.advantage[0], 3.25 - 0.2, 1e-12);
  const Advantages td = compute_advantages(steps, 0.5, 0.0);
  EXPECT_NEAR(td.advantage[0], 1 + 0.5 * 0.3 - 0.2, 1e-12);
  EXPECT_NEAR(td.advantage[2], 3 + 0.5 * 4.0 - 0.1, 1e-12);
}

TEST(Advantages, RejectsOutOfRangeDiscounts) {
  EXPECT_THROW(compute_advantages({}, 1.5, 0.9), Error);
  EXPECT_THROW(compute_advantages({}, 0.9, -0.1), Error);
  EXPECT_TRUE(compute_advantages({}, 0.9, 0.9).advantage.empty());
}
