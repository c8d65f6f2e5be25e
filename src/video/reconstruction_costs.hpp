#pragma once
// The cost functions of the motion reconstruction (video/reconstruct.cpp, seed 003 §5), on the pose
// parameterisation of video/pose_parameters.hpp: the 2D keypoint term, the 3D rotation term, the
// smoothness term (on forward kinematics shared by the frames around it), and the raw estimate's
// fit to 3D keypoints. Internal to the video layer.
#include <ceres/ceres.h>

#include <algorithm>
#include <vector>

#include "video/keypoints.hpp"
#include "video/pose_parameters.hpp"

namespace mimic::reconstruction {

constexpr int kStride = 4;  // derivatives per pass of Ceres's dynamic automatic differentiation

struct Binding {
  int keypoint = 0;
  int point = 0;  // index into pose_positions' output: joints, then sites
};

// Per thread and scalar type (double, or Ceres's Jet), the buffers of the cost functions' forward
// kinematics, so that an evaluation does not allocate.
template <typename T>
struct Scratch {
  std::vector<Vec3T<T>> pos;
  std::vector<QuatT<T>> local, world;
};
template <typename T>
Scratch<T>& scratch() {
  thread_local Scratch<T> s;
  return s;
}

struct Geometry {
  const Skeleton* sk = nullptr;
  std::vector<int> offsets;
  int dofs = 0;
};

// The 2D term of one frame: Σ c ‖x̂ − Π F(q)‖₁ (weighted by w2D).
struct KeypointCost {
  const Geometry* g;
  std::vector<Binding> bindings;
  std::vector<Vec2> target;  // normalised image coordinates
  std::vector<double> scale; // sqrt(2 w2D c)
  double focal;              // in half-heights
  std::vector<double> reweight;  // per residual, the reweighting's sqrt(1 / max(|x|, ε))
  template <typename T>
  bool operator()(T const* const* p, T* r) const {
    Scratch<T>& sc = scratch<T>();
    std::vector<Vec3T<T>>& pos = sc.pos;
    pose_positions(*g->sk, g->offsets, p[0], pos, sc.local, sc.world);
    const T inv_depth = T(focal) / pos[0].z();
    for (std::size_t k = 0; k < bindings.size(); ++k) {
      const Vec3T<T>& x = pos[static_cast<std::size_t>(bindings[k].point)];
      const T du = x.x() * inv_depth - T(target[k].x()), dv = x.y() * inv_depth - T(target[k].y());
      r[2 * k] = T(scale[k] * reweight[2 * k]) * du;
      r[2 * k + 1] = T(scale[k] * reweight[2 * k + 1]) * dv;
    }
    return true;
  }
};

// The 3D term of one frame: w_t Σ_k dist(q̂_k, q_k), the distance 2 sin(θ/2) (θ to within 5 % up
// to 60 degrees): the norm of twice the vector part of q̂⁻¹q, residuals smooth in the quaternion.
struct RotationPriorCost {
  const Geometry* g;
  std::vector<int> joints;  // with rotations of their own
  std::vector<Quat> prior;  // per joint (all joints, indexed by joint)
  double scale;             // sqrt(2 w3D w_t)
  std::vector<double> reweight;  // per joint, as KeypointCost's
  template <typename T>
  bool operator()(T const* const* p, T* r) const {
    std::vector<QuatT<T>>& local = scratch<T>().local;
    local_rotations(*g->sk, g->offsets, p[0], local);
    for (std::size_t i = 0; i < joints.size(); ++i) {
      const QuatT<T>& q = local[static_cast<std::size_t>(joints[i])];
      const Quat& h = prior[static_cast<std::size_t>(joints[i])];
      // vec(h⁻¹ q), sign chosen so that its w is >= 0: norm sin(θ/2)
      const QuatT<T> d = QuatT<T>(T(h.w()), T(-h.x()), T(-h.y()), T(-h.z())) * q;
      const T sign = T(reweight[i] * scale) * (d.w() < T(0) ? T(-2.0) : T(2.0));
      r[3 * i] = sign * d.x();
      r[3 * i + 1] = sign * d.y();
      r[3 * i + 2] = sign * d.z();
    }
    return true;
  }
};

// Every frame's joint positions and, when Ceres asks for them, their derivatives by the frame's
// parameters: computed once per evaluation point (Ceres calls back before each evaluation, the
// parameter blocks holding the point), and shared by the smoothness terms of the frames around it.
class FrameKinematics : public ceres::EvaluationCallback {
 public:
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  FrameKinematics(const Geometry& g, const std::vector<std::vector<double>>& q) : g_(g), q_(q) {}

  void PrepareForEvaluation(bool evaluate_jacobians, bool /*new_evaluation_point*/) override {
    using Jet = ceres::Jet<double, kJetWidth>;
    const auto nj = static_cast<Eigen::Index>(g_.sk->joints.size());
    pos_.resize(q_.size());
    jac_.resize(q_.size());
    std::vector<Vec3T<double>> p;
    std::vector<QuatT<double>> l, w;
    std::vector<Vec3T<Jet>> pj;
    std::vector<QuatT<Jet>> lj, wj;
    std::vector<Jet> x(static_cast<std::size_t>(g_.dofs));
    for (std::size_t f = 0; f < q_.size(); ++f) {
      pose_positions(*g_.sk, g_.offsets, q_[f].data(), p, l, w);
      pos_[f].resize(3 * nj);
      for (Eigen::Index j = 0; j < nj; ++j) pos_[f].segment<3>(3 * j) = p[static_cast<std::size_t>(j)];
      if (!evaluate_jacobians) continue;
      jac_[f].resize(3 * nj, g_.dofs);
      for (int first = 0; first < g_.dofs; first += kJetWidth) {  // kJetWidth derivatives per pass
        for (int d = 0; d < g_.dofs; ++d) {
          x[static_cast<std::size_t>(d)] = Jet(q_[f][static_cast<std::size_t>(d)]);
          if (d >= first && d < first + kJetWidth) x[static_cast<std::size_t>(d)].v[d - first] = 1.0;
        }
        pose_positions(*g_.sk, g_.offsets, x.data(), pj, lj, wj);
        for (Eigen::Index j = 0; j < nj; ++j)
          for (int i = 0; i < 3; ++i)
            for (int d = first; d < std::min(first + kJetWidth, g_.dofs); ++d)
              jac_[f](3 * j + i, d) = pj[static_cast<std::size_t>(j)][i].v[d - first];
      }
    }
  }
  const Eigen::VectorXd& positions(std::size_t frame) const { return pos_[frame]; }
  const RowMajor& jacobian(std::size_t frame) const { return jac_[frame]; }

 private:
  static constexpr int kJetWidth = 8;
  const Geometry& g_;
  const std::vector<std::vector<double>>& q_;
  std::vector<Eigen::VectorXd> pos_;
  std::vector<RowMajor> jac_;
};

// The smoothness term over consecutive frames, Σ_j ‖Δ F_j‖² over the joints: Δ the first
// difference F(q_t) − F(q_t+1) (seed 003's, a velocity: two frames) or the second difference
// F(q_t−1) − 2 F(q_t) + F(q_t+1) (an acceleration: three frames). Positions and derivatives
// from FrameKinematics.
class SmoothnessCost : public ceres::CostFunction {
 public:
  SmoothnessCost(const FrameKinematics& k, std::vector<std::size_t> frames, std::vector<double> coefficients, int residuals, int dofs)
      : k_(k), frames_(std::move(frames)), coef_(std::move(coefficients)) {
    set_num_residuals(residuals);
    for (std::size_t i = 0; i < frames_.size(); ++i) mutable_parameter_block_sizes()->push_back(dofs);
  }
  bool Evaluate(double const* const* /*parameters*/, double* residuals, double** jacobians) const override {
    Eigen::Map<Eigen::VectorXd> r(residuals, num_residuals());
    r.setZero();
    for (std::size_t i = 0; i < frames_.size(); ++i) r += coef_[i] * k_.positions(frames_[i]);
    if (jacobians)
      for (std::size_t i = 0; i < frames_.size(); ++i)
        if (jacobians[i]) {
          const FrameKinematics::RowMajor& jf = k_.jacobian(frames_[i]);
          Eigen::Map<FrameKinematics::RowMajor>(jacobians[i], jf.rows(), jf.cols()) = coef_[i] * jf;
        }
    return true;
  }

 private:
  const FrameKinematics& k_;
  std::vector<std::size_t> frames_;
  std::vector<double> coef_;  // sqrt(2 wsm) times the difference's coefficient of each frame
};

// The raw estimate's fit of one frame's rotations to the 3D keypoints, both about their centroids.
struct WorldKeypointCost {
  const Geometry* g;
  std::vector<Binding> bindings;
  std::vector<Vec3> target;  // centred
  template <typename T>
  bool operator()(T const* const* p, T* r) const {
    Scratch<T>& sc = scratch<T>();
    std::vector<Vec3T<T>>& pos = sc.pos;
    pose_positions(*g->sk, g->offsets, p[0], pos, sc.local, sc.world);
    Vec3T<T> mean = Vec3T<T>::Zero();
    for (const Binding& bd : bindings) mean += pos[static_cast<std::size_t>(bd.point)];
    mean /= T(static_cast<double>(bindings.size()));
    for (std::size_t k = 0; k < bindings.size(); ++k)
      for (int i = 0; i < 3; ++i)
        r[3 * k + static_cast<std::size_t>(i)] = pos[static_cast<std::size_t>(bindings[k].point)][i] - mean[i] - T(target[k][i]);
    return true;
  }
};

template <typename Functor>
ceres::CostFunction* make_cost(Functor* f, int dofs, int blocks, int residuals) {
  auto* c = new ceres::DynamicAutoDiffCostFunction<Functor, kStride>(f);
  for (int i = 0; i < blocks; ++i) c->AddParameterBlock(dofs);
  c->SetNumResiduals(residuals);
  return c;
}

}  // namespace mimic::reconstruction
