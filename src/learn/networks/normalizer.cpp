#include "learn/networks/normalizer.hpp"

#include <string>

#include "core/error.hpp"

namespace mimic {

RunningNormalizer::RunningNormalizer(int size, double clip, double epsilon)
    : mean_(Eigen::VectorXd::Zero(size)), m2_(Eigen::VectorXd::Zero(size)), clip_(clip), epsilon_(epsilon) {
  if (size < 0) throw Error("normalizer: negative size");
  if (!(clip >= 0)) throw Error("normalizer: clip must be >= 0");
}

Eigen::VectorXd RunningNormalizer::variance() const {
  if (count_ <= 0) return Eigen::VectorXd::Zero(mean_.size());
  return m2_ / count_;
}

Eigen::VectorXd RunningNormalizer::stddev() const { return variance().cwiseSqrt(); }

void RunningNormalizer::update(const Eigen::MatrixXd& samples) {
  if (samples.rows() == 0) return;
  if (samples.cols() != mean_.size())
    throw Error("normalizer: samples have " + std::to_string(samples.cols()) + " values, expected " + std::to_string(mean_.size()));
  if (!samples.allFinite()) throw Error("normalizer: a sample holds NaN or infinity");
  RunningNormalizer batch;
  batch.count_ = static_cast<double>(samples.rows());
  batch.mean_ = samples.colwise().mean().transpose();
  batch.m2_ = (samples.rowwise() - batch.mean_.transpose()).colwise().squaredNorm().transpose();
  merge(batch);
}

void RunningNormalizer::update_one(const Eigen::VectorXd& sample) { update(Eigen::MatrixXd(sample.transpose())); }

void RunningNormalizer::merge(const RunningNormalizer& other) {
  if (other.count_ <= 0) return;
  if (other.mean_.size() != mean_.size()) throw Error("normalizer: cannot merge statistics of different sizes");
  const double n = count_ + other.count_;
  const Eigen::VectorXd delta = other.mean_ - mean_;
  mean_ += delta * (other.count_ / n);
  m2_ += other.m2_ + delta.cwiseAbs2() * (count_ * other.count_ / n);
  count_ = n;
}

Eigen::MatrixXd RunningNormalizer::normalize(const Eigen::MatrixXd& samples) const {
  if (samples.cols() != mean_.size())
    throw Error("normalizer: input has " + std::to_string(samples.cols()) + " values, expected " + std::to_string(mean_.size()));
  if (count_ <= 0) return samples;  // no statistics yet: the identity
  const Eigen::RowVectorXd inv = (variance().array() + epsilon_).rsqrt().matrix().transpose();
  Eigen::MatrixXd out = (samples.rowwise() - mean_.transpose()).array().rowwise() * inv.array();
  if (clip_ > 0) out = out.cwiseMax(-clip_).cwiseMin(clip_);
  return out;
}

Eigen::VectorXd RunningNormalizer::normalize_one(const Eigen::VectorXd& sample) const {
  return normalize(Eigen::MatrixXd(sample.transpose())).transpose();
}

void RunningNormalizer::set_state(double count, const Eigen::VectorXd& mean, const Eigen::VectorXd& m2) {
  if (mean.size() != mean_.size() || m2.size() != mean_.size())
    throw Error("normalizer: saved statistics have " + std::to_string(mean.size()) + " values, expected " + std::to_string(mean_.size()));
  if (!(count >= 0) || !mean.allFinite() || !m2.allFinite() || (m2.array() < 0).any())
    throw Error("normalizer: saved statistics are invalid (negative count or variance, or not finite)");
  count_ = count, mean_ = mean, m2_ = m2;
}

}  // namespace mimic
