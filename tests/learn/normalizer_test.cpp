// Running observation statistics: values by hand, exact merging, checkpoint state.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "learn/networks/normalizer.hpp"

using namespace mimic;

namespace {
Eigen::MatrixXd rows(std::initializer_list<std::initializer_list<double>> r) {
  Eigen::MatrixXd m(static_cast<Eigen::Index>(r.size()), static_cast<Eigen::Index>(r.begin()->size()));
  Eigen::Index i = 0;
  for (const auto& row : r) {
    Eigen::Index j = 0;
    for (double x : row) m(i, j++) = x;
    ++i;
  }
  return m;
}
}  // namespace

TEST(Normalizer, StatisticsAndNormalisedValuesByHand) {
  RunningNormalizer n(2, 10.0, 0.0);
  n.update(rows({{1, 10}, {3, 10}, {5, 40}}));
  EXPECT_DOUBLE_EQ(n.count(), 3);
  EXPECT_NEAR(n.mean()[0], 3, 1e-12);
  EXPECT_NEAR(n.mean()[1], 20, 1e-12);
  EXPECT_NEAR(n.variance()[0], 8.0 / 3, 1e-12);  // population variance
  EXPECT_NEAR(n.variance()[1], 200, 1e-12);
  const Eigen::VectorXd z = n.normalize_one(Eigen::Vector2d(5, 40));
  EXPECT_NEAR(z[0], 2 / std::sqrt(8.0 / 3), 1e-12);
  EXPECT_NEAR(z[1], 20 / std::sqrt(200.0), 1e-12);
  EXPECT_DOUBLE_EQ(n.normalize_one(Eigen::Vector2d(1e6, -1e6))[0], 10.0);  // clipped
  EXPECT_DOUBLE_EQ(n.normalize_one(Eigen::Vector2d(1e6, -1e6))[1], -10.0);
}

TEST(Normalizer, IsTheIdentityBeforeAnySample) {
  RunningNormalizer n(2);
  EXPECT_EQ(n.normalize_one(Eigen::Vector2d(3, -4)), Eigen::Vector2d(3, -4));
}

TEST(Normalizer, MergingTwoEqualsOneOverTheUnion) {
  RunningNormalizer a(3), b(3), all(3);
  const Eigen::MatrixXd x = Eigen::MatrixXd::Random(7, 3) * 5, y = Eigen::MatrixXd::Random(12, 3) + Eigen::MatrixXd::Constant(12, 3, 4);
  a.update(x);
  b.update(Eigen::MatrixXd(y.topRows(5)));
  b.update(Eigen::MatrixXd(y.bottomRows(7)));  // incremental updates too
  Eigen::MatrixXd xy(19, 3);
  xy << x, y;
  all.update(xy);
  a.merge(b);
  EXPECT_DOUBLE_EQ(a.count(), 19);
  EXPECT_LT((a.mean() - all.mean()).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((a.variance() - all.variance()).cwiseAbs().maxCoeff(), 1e-12);
  // Against the textbook two-pass variance.
  const Eigen::RowVectorXd mu = xy.colwise().mean();
  const Eigen::RowVectorXd var = (xy.rowwise() - mu).colwise().squaredNorm() / 19.0;
  EXPECT_LT((a.variance().transpose() - var).cwiseAbs().maxCoeff(), 1e-12);
  RunningNormalizer empty(3);
  a.merge(empty);
  EXPECT_DOUBLE_EQ(a.count(), 19);
}

TEST(Normalizer, RejectsBadInputAndBadSavedState) {
  RunningNormalizer n(2);
  EXPECT_THROW(n.update(Eigen::MatrixXd(Eigen::MatrixXd::Zero(1, 3))), Error);
  EXPECT_THROW(n.update(rows({{1, NAN}})), Error);
  EXPECT_THROW(n.set_state(1, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()), Error);
  EXPECT_THROW(n.set_state(-1, Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()), Error);
  EXPECT_THROW(n.set_state(2, Eigen::Vector2d::Zero(), Eigen::Vector2d(-1, 0)), Error);
  RunningNormalizer other(3);
  other.update(rows({{1, 2, 3}}));
  EXPECT_THROW(n.merge(other), Error);
}
