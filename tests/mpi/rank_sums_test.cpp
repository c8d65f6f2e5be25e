// What two ranks of one run agree on (learn/trainer/rank_sums.hpp), run as `mpirun -np 2
// mimic_mpi_tests`: each rank holds its own part of the data, and the result on both must be
// what one process would compute from all of it (values worked out by hand below).
#include <gtest/gtest.h>

#include "core/blas_kernel.hpp"
#include "learn/trainer/rank_sums.hpp"
#include "learn/trainer/ranks.hpp"

namespace mimic {
namespace {

#define REQUIRE_TWO_RANKS() \
  if (ranks::size() != 2) GTEST_SKIP() << "run under mpirun -np 2 (this process is one of " << ranks::size() << ")"

TEST(RankSums, ANormaliserHoldsTheStatisticsOfEveryRanksRows) {
  REQUIRE_TWO_RANKS();
  // Rank 0 has the rows (1, 2) and (3, 4); rank 1 has (5, 6). All three: mean (3, 4); squared
  // deviations 4 + 0 + 4 = 8 per column, population variance 8/3.
  Eigen::MatrixXd mine = ranks::rank() == 0 ? Eigen::MatrixXd{{1, 2}, {3, 4}} : Eigen::MatrixXd{{5, 6}};
  RunningNormalizer norm(2);
  update_over_ranks(norm, mine);
  EXPECT_DOUBLE_EQ(norm.count(), 3);
  EXPECT_DOUBLE_EQ(norm.mean()[0], 3);
  EXPECT_DOUBLE_EQ(norm.mean()[1], 4);
  EXPECT_NEAR(norm.variance()[0], 8.0 / 3, 1e-12);
  EXPECT_NEAR(norm.variance()[1], 8.0 / 3, 1e-12);
  // A second batch where rank 1 has no rows: rank 0 adds (7, 8). Four rows of the first column:
  // 1, 3, 5, 7: mean 4, squared deviations 9 + 1 + 1 + 9 = 20, variance 5.
  update_over_ranks(norm, ranks::rank() == 0 ? Eigen::MatrixXd{{7, 8}} : Eigen::MatrixXd(0, 2));
  EXPECT_DOUBLE_EQ(norm.count(), 4);
  EXPECT_DOUBLE_EQ(norm.mean()[0], 4);
  EXPECT_NEAR(norm.variance()[0], 5.0, 1e-12);
}

TEST(RankSums, GradientsBecomeTheRanksMean) {
  REQUIRE_TWO_RANKS();
  torch::Tensor w = torch::zeros({2}, torch::requires_grad());
  torch::Tensor b = torch::zeros({1, 1}, torch::requires_grad());
  // Rank 0: dL/dw = (1, 2), dL/db = 10; rank 1: (3, 6) and 30. The mean: (2, 4) and 20.
  const double k = ranks::rank() == 0 ? 1.0 : 3.0;
  const torch::Tensor loss = (w * torch::tensor({k, 2 * k})).sum() + 10 * k * b.sum();
  loss.backward();
  average_gradients({w, b}, ranks::Channel::policy);
  EXPECT_FLOAT_EQ(w.grad()[0].item<float>(), 2.0f);
  EXPECT_FLOAT_EQ(w.grad()[1].item<float>(), 4.0f);
  EXPECT_FLOAT_EQ(b.grad()[0][0].item<float>(), 20.0f);
  EXPECT_DOUBLE_EQ(mean_over_ranks(ranks::rank() == 0 ? 0.5 : 1.5, ranks::Channel::value), 1.0);
}

TEST(RankSums, MomentsAreThoseOfAllRowsTogether) {
  REQUIRE_TWO_RANKS();
  // Rank 0: 1 and 3; rank 1: 5. Mean 3; unbiased variance (4 + 0 + 4) / 2 = 4.
  const torch::Tensor rows = ranks::rank() == 0 ? torch::tensor({1.0f, 3.0f}).unsqueeze(1) : torch::tensor({5.0f}).unsqueeze(1);
  const Moments m = moments_over_ranks(rows);
  EXPECT_DOUBLE_EQ(m.count, 3);
  EXPECT_FLOAT_EQ(m.mean[0].item<float>(), 3.0f);
  EXPECT_FLOAT_EQ(m.variance[0].item<float>(), 4.0f);
}

TEST(RankSums, RanksAgreeOnAMinimumAStopAndGatherTheirStates) {
  REQUIRE_TWO_RANKS();
  EXPECT_DOUBLE_EQ(ranks::minimum(ranks::rank() == 0 ? 7.0 : 3.0), 3.0);
  EXPECT_TRUE(ranks::any(ranks::rank() == 1));
  EXPECT_FALSE(ranks::any(false));
  const std::vector<std::string> all = ranks::gather(ranks::rank() == 0 ? "a" : "state\nof rank 1\n");
  if (ranks::rank() == 0) {
    ASSERT_EQ(all.size(), 2u);
    EXPECT_EQ(all[0], "a");
    EXPECT_EQ(all[1], "state\nof rank 1\n");
  } else {
    EXPECT_TRUE(all.empty());
  }
}

}  // namespace
}  // namespace mimic

int main(int argc, char** argv) {
  mimic::pin_blas_kernel(argv);
  mimic::ranks::init(argc, argv);
  testing::InitGoogleTest(&argc, argv);
  const int code = RUN_ALL_TESTS();
  // Both ranks' verdicts: a failure on rank 1 fails the program mpirun reports.
  const bool failed = mimic::ranks::any(code != 0);
  mimic::ranks::finalize();
  return failed ? 1 : 0;
}
