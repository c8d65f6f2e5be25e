#include "learn/imitation/adaptive_init.hpp"

#include <cmath>
#include <utility>

#include "core/error.hpp"

namespace mimic {

Eigen::VectorXd state_features(const Skeleton& sk, const Pose& pose, const PoseVelocity& vel) {
  std::vector<double> f;
  auto put = [&](const Vec3& v) { f.insert(f.end(), {v.x(), v.y(), v.z()}); };
  f.push_back(pose.root_pos.z());
  put(quat_to_rotvec(heading_rotation(-heading_angle(pose.rot[0])) * pose.rot[0]));
  for (std::size_t j = 1; j < sk.joints.size(); ++j) {
    const Joint& jt = sk.joints[j];
    if (jt.type == JointType::Spherical) put(quat_to_rotvec(pose.rot[j]));
    if (jt.type == JointType::Revolute) f.push_back(revolute_angle(jt, pose.rot[j]));
  }
  put(vel.root_lin);
  put(vel.root_ang);
  for (std::size_t j = 1; j < sk.joints.size(); ++j) {
    const Joint& jt = sk.joints[j];
    if (jt.type == JointType::Spherical) put(vel.joint_ang[j]);
    if (jt.type == JointType::Revolute) f.push_back(vel.joint_ang[j].dot(jt.axis));
  }
  return Eigen::Map<const Eigen::VectorXd>(f.data(), static_cast<Eigen::Index>(f.size()));
}

AdaptiveInit::AdaptiveInit(std::shared_ptr<const Clip> clip, const Skeleton& sk, const AdaptiveInitConfig& cfg)
    : clip_(std::move(clip)), sk_(sk), cfg_(cfg) {
  if (!clip_) throw Error("adaptive initialisation needs a reference clip");
  if (clip_->skeleton.num_joints() != sk.num_joints()) throw Error("adaptive initialisation: clip '" + clip_->name + "' does not fit the character");
  if (clip_->num_frames() < 2) throw Error("adaptive initialisation: clip '" + clip_->name + "' has fewer than 2 frames");
  if (cfg.components < 1) throw Error("adaptive initialisation: 'components' must be at least 1");
  if (!(cfg.step >= 0) || !(cfg.std_scale >= 0) || !(cfg.min_std > 0) || cfg.batch_episodes < 1)
    throw Error("adaptive initialisation: step and std_scale must be non-negative, min_std positive, batch_episodes at least 1");
  // Per-dimension sample std of the clip's state features over its frames.
  const std::vector<PoseVelocity> vel = clip_velocities(*clip_);
  Eigen::MatrixXd features(clip_->num_frames(), 0);
  for (int f = 0; f < clip_->num_frames(); ++f) {
    const auto u = static_cast<std::size_t>(f);
    const Eigen::VectorXd row = state_features(sk, clip_->frames[u], vel[u]);
    if (f == 0) features.resize(clip_->num_frames(), row.size());
    features.row(f) = row.transpose();
  }
  const Eigen::RowVectorXd mean = features.colwise().mean();
  initial_std_ = ((features.rowwise() - mean).array().square().colwise().sum() / (features.rows() - 1)).sqrt().transpose();
  initial_std_ = (initial_std_ * cfg.std_scale).cwiseMax(cfg.min_std);
  mean_ = Eigen::MatrixXd::Zero(cfg.components, initial_std_.size());
  log_std_ = initial_std_.array().log().transpose().replicate(cfg.components, 1);
}

double AdaptiveInit::phase_time(int component) const { return clip_->duration() * component / cfg_.components; }

AdaptiveInit::Draw AdaptiveInit::draw(std::mt19937_64& rng) const {
  std::uniform_int_distribution<int> pick(0, cfg_.components - 1);
  std::normal_distribution<double> normal;
  Draw d;
  d.component = pick(rng);
  d.x.resize(dims());
  for (int i = 0; i < dims(); ++i) d.x[i] = mean_(d.component, i) + std::exp(log_std_(d.component, i)) * normal(rng);
  return d;
}

InitState AdaptiveInit::state(int component, const Eigen::VectorXd& x) const {
  if (x.size() != dims()) throw Error("adaptive initialisation: " + std::to_string(x.size()) + " offsets for " + std::to_string(dims()) + " dimensions");
  InitState s = init_state_from_clip(*clip_, phase_time(component));
  Eigen::Index k = 0;
  auto vec3 = [&] {
    const Vec3 v(x[k], x[k + 1], x[k + 2]);
    k += 3;
    return v;
  };
  s.pose.root_pos.z() += x[k++];
  s.pose.rot[0] = (s.pose.rot[0] * rotvec_to_quat(vec3())).normalized();
  for (std::size_t j = 1; j < sk_.joints.size(); ++j) {
    const Joint& jt = sk_.joints[j];
    if (jt.type == JointType::Spherical) s.pose.rot[j] = (s.pose.rot[j] * rotvec_to_quat(vec3())).normalized();
    if (jt.type == JointType::Revolute) {
      double angle = revolute_angle(jt, s.pose.rot[j]) + x[k++];
      if (!jt.limits.empty()) angle = std::clamp(angle, jt.limits[0].first, jt.limits[0].second);
      s.pose.rot[j] = Quat(Eigen::AngleAxisd(angle, jt.axis));
    }
  }
  s.velocity.root_lin += vec3();
  s.velocity.root_ang += vec3();
  for (std::size_t j = 1; j < sk_.joints.size(); ++j) {
    const Joint& jt = sk_.joints[j];
    if (jt.type == JointType::Spherical) s.velocity.joint_ang[j] += vec3();
    if (jt.type == JointType::Revolute) s.velocity.joint_ang[j] += jt.axis * x[k++];
  }
  return s;
}

void AdaptiveInit::update(const std::vector<Outcome>& batch) {
  for (int c = 0; c < cfg_.components; ++c) {
    double baseline = 0;
    int n = 0;
    for (const Outcome& o : batch)
      if (o.component == c) baseline += o.ret, ++n;
    if (n < 2) continue;
    baseline /= n;
    Eigen::VectorXd grad_mean = Eigen::VectorXd::Zero(dims()), grad_log_std = Eigen::VectorXd::Zero(dims());
    const Eigen::ArrayXd sigma = log_std_.row(c).array().exp().transpose();
    for (const Outcome& o : batch) {
      if (o.component != c) continue;
      if (o.x.size() != dims()) throw Error("adaptive initialisation: an outcome with the wrong number of offsets");
      // Natural gradients of the Gaussian log-density: d/dmu = (x - mu) / sigma^2 and
      // d/dlog sigma = z^2 - 1, each times the inverse Fisher information (sigma^2 and 1/2).
      const Eigen::ArrayXd z = (o.x - mean_.row(c).transpose()).array() / sigma;
      const double advantage = o.ret - baseline;
      grad_mean += (advantage * z * sigma).matrix();
      grad_log_std += (0.5 * advantage * (z.square() - 1.0)).matrix();
    }
    mean_.row(c) += (cfg_.step / n) * grad_mean.transpose();
    log_std_.row(c) += (cfg_.step / n) * grad_log_std.transpose();
    log_std_.row(c) = log_std_.row(c).cwiseMax(std::log(cfg_.min_std));
  }
}

void AdaptiveInit::set_parameters(const Eigen::MatrixXd& means, const Eigen::MatrixXd& log_std) {
  if (means.rows() != cfg_.components || means.cols() != dims() || log_std.rows() != cfg_.components || log_std.cols() != dims())
    throw Error("adaptive initialisation: saved parameters are " + std::to_string(means.rows()) + " x " + std::to_string(means.cols()) +
                ", the config asks for " + std::to_string(cfg_.components) + " x " + std::to_string(dims()));
  mean_ = means;
  log_std_ = log_std;
}

AdaptiveInitEnv::AdaptiveInitEnv(std::unique_ptr<Env> inner, std::shared_ptr<const AdaptiveInit> dist, double gamma)
    : inner_(std::move(inner)), character_(dynamic_cast<CharacterEnv*>(inner_.get())), dist_(std::move(dist)), gamma_(gamma) {
  if (!character_) throw Error("adaptive initialisation needs a character environment with a reference clip (e.g. tracking)");
}

Eigen::VectorXd AdaptiveInitEnv::reset(std::mt19937_64& rng) {
  const AdaptiveInit::Draw d = dist_->draw(rng);
  current_ = AdaptiveInit::Outcome{d.component, d.x, 0.0};
  discount_ = 1.0;
  return character_->reset(dist_->state(d.component, d.x));
}

StepResult AdaptiveInitEnv::step(const Eigen::VectorXd& action) {
  StepResult r = inner_->step(action);
  current_.ret += discount_ * r.reward();
  discount_ *= gamma_;
  if (r.done()) done_.push_back(current_);
  return r;
}

std::vector<AdaptiveInit::Outcome> AdaptiveInitEnv::take_outcomes() { return std::exchange(done_, {}); }

}  // namespace mimic
