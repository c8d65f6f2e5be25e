#pragma once
// Running mean and standard deviation of observations (seed 000's "online z-filtering", seed
// 002's running mean/std): statistics in double precision, merged exactly with Chan et al.'s
// parallel formula so that statistics gathered by several workers combine into one.
#include <Eigen/Core>

namespace mimic {

class RunningNormalizer {
 public:
  RunningNormalizer() = default;
  // `clip` bounds normalised values to +-clip (0: no clipping); `epsilon` guards a zero variance.
  explicit RunningNormalizer(int size, double clip = 10.0, double epsilon = 1e-8);

  int size() const { return static_cast<int>(mean_.size()); }
  double count() const { return count_; }
  const Eigen::VectorXd& mean() const { return mean_; }
  // Population variance (divided by the count); zero before any sample.
  Eigen::VectorXd variance() const;
  Eigen::VectorXd stddev() const;
  double clip() const { return clip_; }

  // Adds the rows of `samples` (one sample per row). Error on a wrong width or a non-finite value.
  void update(const Eigen::MatrixXd& samples);
  void update_one(const Eigen::VectorXd& sample);
  // Statistics of the union of both sample sets (Chan et al. 1979).
  void merge(const RunningNormalizer& other);

  // (x - mean) / sqrt(var + epsilon), clipped; rows of a matrix or a single vector. Before the
  // first sample it is the identity (a variance of 0 would blow inputs up).
  Eigen::MatrixXd normalize(const Eigen::MatrixXd& samples) const;
  Eigen::VectorXd normalize_one(const Eigen::VectorXd& sample) const;

  // Raw state for checkpoints; set_state checks that the sizes agree.
  const Eigen::VectorXd& m2() const { return m2_; }
  double epsilon() const { return epsilon_; }
  void set_state(double count, const Eigen::VectorXd& mean, const Eigen::VectorXd& m2);

 private:
  double count_ = 0.0;
  Eigen::VectorXd mean_, m2_;  // m2: sum of squared deviations from the mean
  double clip_ = 10.0, epsilon_ = 1e-8;
};

}  // namespace mimic
