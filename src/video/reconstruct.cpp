#include "video/reconstruct.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/error.hpp"
#include "core/file_io.hpp"
#include "core/yaml_reader.hpp"
#include "motion/kinematics.hpp"
#include "video/camera.hpp"
#include "video/ground_plane.hpp"
#include "video/pose_parameters.hpp"
#include "video/reconstruction_costs.hpp"

namespace mimic {

namespace {

// The L1 norms of the 2D and 3D terms are minimised by iteratively reweighted least squares:
// each round solves with every residual x weighted by 1/max(|x|, ε) from the round before, whose
// fixed point minimises Σ|x|. ε: 2 pixels at 720p for keypoints, 1 degree for rotations.
constexpr double kPixelEpsilon = 0.005;  // half-heights
constexpr double kAngleEpsilon = 0.0175; // radians
constexpr int kReweightRounds = 4;
constexpr double kMinDepth = 0.3;  // metres in front of the camera

using namespace reconstruction;

// Joint limits as bounds on the parameters (a spherical joint's on its rotation vector's
// components, the per-axis angles for small turns).
void bound_joints(ceres::Problem& problem, double* block, const Skeleton& sk, const std::vector<int>& offsets) {
  for (std::size_t j = 1; j < sk.joints.size(); ++j) {
    const Joint& jt = sk.joints[j];
    if (offsets[j] < 0 || jt.limits.empty()) continue;
    const int n = jt.type == JointType::Revolute ? 1 : 3;
    if (static_cast<int>(jt.limits.size()) != n) continue;
    for (int i = 0; i < n; ++i) {
      const auto [lo, hi] = jt.limits[static_cast<std::size_t>(i)];
      if (!(lo < hi)) continue;
      double& v = block[offsets[j] + i];
      v = std::clamp(v, lo, hi);
      problem.SetParameterLowerBound(block, offsets[j] + i, lo);
      problem.SetParameterUpperBound(block, offsets[j] + i, hi);
    }
  }
}

std::vector<Vec3> positions(const Geometry& g, const std::vector<double>& p) {
  std::vector<Vec3> pos;
  std::vector<Quat> a, b;
  pose_positions(*g.sk, g.offsets, p.data(), pos, a, b);
  return pos;
}

// The rotation best turning centred points `from` onto centred `to` (Kabsch, via Eigen's Umeyama).
Quat best_rotation(const std::vector<Vec3>& from, const std::vector<Vec3>& to) {
  Eigen::Matrix3Xd a(3, static_cast<Eigen::Index>(from.size())), b(3, static_cast<Eigen::Index>(to.size()));
  for (std::size_t i = 0; i < from.size(); ++i) a.col(static_cast<Eigen::Index>(i)) = from[i], b.col(static_cast<Eigen::Index>(i)) = to[i];
  const Eigen::Matrix4d m = Eigen::umeyama(a, b, false);
  return Quat(Mat3(m.topLeftCorner<3, 3>())).normalized();
}

struct FrameData {
  std::vector<Binding> seen;       // bindings with confidence > 0
  std::vector<Vec2> target;        // normalised
  std::vector<double> confidence;
  std::vector<Vec3> world;         // per binding (all bindings), centred later
  bool fit = false;
};

std::vector<int> rotating_joints(const Skeleton& sk, const std::vector<int>& offsets) {
  std::vector<int> out;
  for (std::size_t j = 0; j < sk.joints.size(); ++j)
    if (offsets[j] >= 0) out.push_back(static_cast<int>(j));
  return out;
}

// Keypoints onto the character's joints and sites (by name, or by `map`); names that bind to
// nothing go to `unused`. Throws Error with fewer than 4 bindings.
std::vector<Binding> bind_keypoints(const KeypointTrack& track, const Skeleton& sk, const KeypointMap& map, const std::string& where,
                                    std::vector<std::string>& unused) {
  std::vector<Binding> bindings;
  auto point_of = [&](const std::string& name) {
    if (const int j = sk.find(name); j >= 0) return j;
    if (const int s = sk.find_site(name); s >= 0) return sk.num_joints() + s;
    return -1;
  };
  if (map.pairs.empty()) {
    for (std::size_t k = 0; k < track.names.size(); ++k) {
      const int p = point_of(track.names[k]);
      if (p >= 0) bindings.push_back({static_cast<int>(k), p});
      else unused.push_back(track.names[k]);
    }
  } else {
    for (const auto& [kp, joint] : map.pairs) {
      const int k = track.find(kp);
      if (k < 0) throw Error(map.source + ": keypoint '" + kp + "' is not among " + where + "'s keypoints");
      const int p = point_of(joint);
      if (p < 0) throw Error(map.source + ": '" + joint + "' (for keypoint '" + kp + "') is neither a joint nor a site of the character");
      bindings.push_back({k, p});
    }
    for (const std::string& n : track.names)
      if (std::none_of(map.pairs.begin(), map.pairs.end(), [&](const auto& pr) { return pr.first == n; })) unused.push_back(n);
  }
  if (bindings.size() < 4)
    throw Error(where + ": only " + std::to_string(bindings.size()) +
                " of its keypoints name joints or sites of the character (4 at least); give a keypoint map (--map)");
  return bindings;
}

// Frame `t`'s keypoints on the bindings; fit when it has `min_keypoints` seen and a 3D estimate.
FrameData frame_data(const KeypointTrack& track, int t, const std::vector<Binding>& bindings, int min_keypoints) {
  const KeypointFrame& f = track.frames[static_cast<std::size_t>(t)];
  FrameData d;
  if (f.empty()) return d;
  const double half = 0.5 * track.height;
  for (const Binding& b : bindings) {
    const auto k = static_cast<std::size_t>(b.keypoint);
    if (f.confidence[k] > 0) {
      d.seen.push_back(b);
      d.target.emplace_back((f.pixel[k].x() - 0.5 * track.width) / half, (f.pixel[k].y() - half) / half);
      d.confidence.push_back(f.confidence[k]);
    }
    if (!f.world.empty()) d.world.push_back(f.world[k]);
  }
  d.fit = static_cast<int>(d.seen.size()) >= min_keypoints && !f.world.empty();
  return d;
}

// One frame's raw estimate from `p` (the frame before's, or the rest pose ahead of the camera):
// the joint rotations fitted to the centred 3D keypoints, then the pelvis's place in closed form
// from the 2D ones (weak perspective: x̂ = f/Z (X_r + a)). Adds the solver's iterations.
void fit_frame(const Geometry& g, const std::vector<Binding>& bindings, const FrameData& d, double focal, std::vector<double>& p, int& iterations) {
  std::vector<Vec3> target = d.world;
  Vec3 centre = Vec3::Zero();
  for (const Vec3& w : target) centre += w / static_cast<double>(target.size());
  for (Vec3& w : target) w -= centre;
  {  // the root's rotation first, from the starting pose turned onto the keypoints
    const std::vector<Vec3> pos = positions(g, p);
    std::vector<Vec3> from;
    Vec3 c = Vec3::Zero();
    for (const Binding& b : bindings) from.push_back(pos[static_cast<std::size_t>(b.point)]), c += from.back() / static_cast<double>(bindings.size());
    for (Vec3& v : from) v -= c;
    const Quat turn = best_rotation(from, target);
    const Vec3 rv = quat_to_rotvec((turn * rotvec_to_quat(Vec3(p[3], p[4], p[5]))).normalized());
    p[3] = rv.x(), p[4] = rv.y(), p[5] = rv.z();
  }
  ceres::Problem problem;
  auto* f = new WorldKeypointCost{&g, bindings, target};
  problem.AddResidualBlock(make_cost(f, g.dofs, 1, 3 * static_cast<int>(bindings.size())), nullptr, p.data());
  problem.SetManifold(p.data(), new ceres::SubsetManifold(g.dofs, {0, 1, 2}));
  bound_joints(problem, p.data(), *g.sk, g.offsets);
  ceres::Solver::Options so;
  so.linear_solver_type = ceres::DENSE_QR;
  so.max_num_iterations = 50;
  so.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(so, &problem, &summary);
  iterations += static_cast<int>(summary.iterations.size());
  // The pelvis: scale and shift of the posed points (relative to the root) onto the 2D ones.
  const std::vector<Vec3> pos = positions(g, p);
  Vec2 ma = Vec2::Zero(), mb = Vec2::Zero();
  double wsum = 0;
  for (std::size_t k = 0; k < d.seen.size(); ++k) {
    const Vec3 a = pos[static_cast<std::size_t>(d.seen[k].point)] - pos[0];
    ma += d.confidence[k] * a.head<2>(), mb += d.confidence[k] * d.target[k], wsum += d.confidence[k];
  }
  ma /= wsum, mb /= wsum;
  double num = 0, den = 0;
  for (std::size_t k = 0; k < d.seen.size(); ++k) {
    const Vec2 a = (pos[static_cast<std::size_t>(d.seen[k].point)] - pos[0]).head<2>() - ma;
    num += d.confidence[k] * a.dot(d.target[k] - mb), den += d.confidence[k] * a.squaredNorm();
  }
  const double s = num > 0 && den > 0 ? num / den : focal / 5.0;
  const Vec2 tau = mb - s * ma;
  p[2] = std::max(focal / s, kMinDepth);
  p[0] = tau.x() / s, p[1] = tau.y() / s;
}

// The starting pose before any frame is fitted: the rest pose 5 m ahead of the camera.
std::vector<double> rest_ahead(const Geometry& g) {
  std::vector<double> p(static_cast<std::size_t>(g.dofs), 0.0);
  p.at(2) = 5.0;
  return p;
}

// Poses (parameter vectors, in the camera's frame) as a clip in the world the ground gives: z up,
// x the camera's view along the floor, `origin` (in the camera's frame) at the world's origin.
Clip to_world(const Geometry& g, const GroundFit& ground, const Vec3& origin, const std::vector<std::vector<double>>& params, double fps,
              const std::string& name) {
  const Mat3& world_from_cam = ground.world_from_camera;
  const Quat turn(world_from_cam);
  Clip c;
  c.name = name;
  c.skeleton = *g.sk;
  c.fps = fps;
  for (const auto& p : params) {
    Pose pose = parameters_to_pose(*g.sk, p.data());
    pose.root_pos = world_from_cam * (pose.root_pos - origin);
    pose.rot[0] = canonical((turn * pose.rot[0]).normalized());
    c.frames.push_back(std::move(pose));
  }
  return c;
}

double focal_of(const KeypointTrack& track, const ReconstructionOptions& o) {
  const double fov = o.fov_deg > 0 ? o.fov_deg : track.fov_deg > 0 ? track.fov_deg : kDefaultFovDeg;
  return 1.0 / std::tan(0.5 * deg_to_rad(fov));  // in half-heights
}

}  // namespace

KeypointMap load_keypoint_map(const std::filesystem::path& path) {
  const YamlReader r(path.string());
  const YAML::Node root = r.parse(read_text_file(path), path.string() + ": not a keypoint map (YAML)");
  if (!root.IsMap()) throw Error(path.string() + ": a keypoint map is a mapping with 'keypoints'");
  const YAML::Node kp = r.member(root, "keypoints", "the map");
  if (!kp.IsMap()) r.fail(kp, "'keypoints': expected a mapping of keypoint names to joint or site names");
  KeypointMap m;
  m.source = path.string();
  for (const auto& e : kp) m.pairs.emplace_back(r.text(e.first, "a keypoint name"), r.text(e.second, "'" + e.first.as<std::string>() + "'"));
  return m;
}

Reconstruction reconstruct_motion(const KeypointTrack& track, const Skeleton& sk, const KeypointMap& map, const ReconstructionOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  track.validate();
  sk.validate();
  const std::string where = track.source.empty() ? std::string("keypoints") : track.source;
  Reconstruction out;
  ReconstructionReport& rep = out.report;

  const std::vector<Binding> bindings = bind_keypoints(track, sk, map, where, rep.unused_keypoints);

  Geometry g{&sk, parameter_offsets(sk), sk.dof_count()};
  const double focal = focal_of(track, o);
  const int n = track.num_frames();

  // Which frames can be fitted.
  std::vector<FrameData> data(static_cast<std::size_t>(n));
  bool any_world = false;
  for (int t = 0; t < n; ++t) {
    data[static_cast<std::size_t>(t)] = frame_data(track, t, bindings, o.min_keypoints);
    any_world = any_world || !track.frames[static_cast<std::size_t>(t)].world.empty();
  }
  if (!any_world)
    throw Error(where + ": no frame has 3D keypoints (\"world\"); the reconstruction starts from a per-frame 3D estimate "
                        "(mimic video keypoints gives one)");
  for (int t = 0; t < n; ++t)
    if (!data[static_cast<std::size_t>(t)].fit) rep.unfit.push_back(t);

  // The longest stretch whose inner gaps of unfit frames are at most max_bridge long.
  int best_first = 0, best_last = -1, best_count = 0;
  for (int t = 0; t < n;) {
    if (!data[static_cast<std::size_t>(t)].fit) { ++t; continue; }
    int last = t, count = 0, u = t;
    while (u < n) {
      if (data[static_cast<std::size_t>(u)].fit) { last = u, ++count, ++u; continue; }
      int gap_end = u;
      while (gap_end < n && !data[static_cast<std::size_t>(gap_end)].fit) ++gap_end;
      if (gap_end - u > o.max_bridge || gap_end == n) break;
      u = gap_end;
    }
    if (count > best_count) best_first = t, best_last = last, best_count = count;
    t = last + 1;
  }
  if (best_count < o.min_frames)
    throw Error(where + ": the longest stretch of frames that can be fitted has " + std::to_string(best_count) + " frames, fewer than " +
                std::to_string(o.min_frames) + " (a frame needs " + std::to_string(o.min_keypoints) +
                " keypoints seen and a 3D estimate); too short to reconstruct");
  rep.first_frame = best_first;
  for (int t : rep.unfit) (t > best_first && t < best_last ? rep.bridged : rep.cut).push_back(t);
  for (int t = 0; t < n; ++t)
    if ((t < best_first || t > best_last) && data[static_cast<std::size_t>(t)].fit) rep.cut.push_back(t);
  std::sort(rep.cut.begin(), rep.cut.end());
  const int m = best_last - best_first + 1;

  // Raw estimate, frame by frame, each from the one before.
  std::vector<std::vector<double>> raw(static_cast<std::size_t>(m), std::vector<double>(static_cast<std::size_t>(g.dofs), 0.0));
  std::vector<double> previous = rest_ahead(g);
  for (int i = 0; i < m; ++i) {
    const FrameData& d = data[static_cast<std::size_t>(best_first + i)];
    if (!d.fit) continue;  // bridged: filled below
    std::vector<double>& p = raw[static_cast<std::size_t>(i)];
    p = previous;
    fit_frame(g, bindings, d, focal, p, rep.raw_iterations);
    previous = p;
  }
  // Bridged frames: the parameters interpolated between the fitted frames around them.
  for (int i = 0; i < m;) {
    if (data[static_cast<std::size_t>(best_first + i)].fit) { ++i; continue; }
    int j = i;
    while (!data[static_cast<std::size_t>(best_first + j)].fit) ++j;
    for (int k = i; k < j; ++k) {
      const double a = static_cast<double>(k - i + 1) / (j - i + 1);
      for (int q = 0; q < g.dofs; ++q)
        raw[static_cast<std::size_t>(k)][static_cast<std::size_t>(q)] =
            (1 - a) * raw[static_cast<std::size_t>(i - 1)][static_cast<std::size_t>(q)] + a * raw[static_cast<std::size_t>(j)][static_cast<std::size_t>(q)];
    }
    i = j;
  }

  // The terms, evaluated plainly (also the report's before and after).
  const std::vector<int> rotating = rotating_joints(sk, g.offsets);
  std::vector<std::vector<Quat>> prior(static_cast<std::size_t>(m));
  std::vector<double> weight3d(static_cast<std::size_t>(m), 0.0);
  auto reprojection = [&](const FrameData& d, const std::vector<Vec3>& pos, bool l1) {
    double sum = 0;
    for (std::size_t k = 0; k < d.seen.size(); ++k) {
      const Vec3& x = pos[static_cast<std::size_t>(d.seen[k].point)];
      const Vec2 e = focal * x.head<2>() / pos[0].z() - d.target[k];
      sum += d.confidence[k] * (l1 ? e.lpNorm<1>() : e.norm());
    }
    return sum;
  };
  for (int i = 0; i < m; ++i) {
    std::vector<Quat> local;
    local_rotations(sk, g.offsets, raw[static_cast<std::size_t>(i)].data(), local);
    prior[static_cast<std::size_t>(i)] = local;
    const FrameData& d = data[static_cast<std::size_t>(best_first + i)];
    if (d.fit) weight3d[static_cast<std::size_t>(i)] = std::exp(-reprojection(d, positions(g, raw[static_cast<std::size_t>(i)]), false));
  }
  auto terms = [&](const std::vector<std::vector<double>>& params) {
    ReconstructionTerms tm;
    std::vector<Vec3> last, before_last;
    for (int i = 0; i < m; ++i) {
      const std::vector<Vec3> pos = positions(g, params[static_cast<std::size_t>(i)]);
      const FrameData& d = data[static_cast<std::size_t>(best_first + i)];
      if (d.fit) {
        tm.l2d += reprojection(d, pos, true);
        std::vector<Quat> local;
        local_rotations(sk, g.offsets, params[static_cast<std::size_t>(i)].data(), local);
        for (int j : rotating) tm.l3d += weight3d[static_cast<std::size_t>(i)] * rotation_distance(local[static_cast<std::size_t>(j)], prior[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)]);
      }
      if (o.smoothness == Smoothness::Velocity && i > 0)
        for (std::size_t j = 0; j < sk.joints.size(); ++j) tm.lsm += (pos[j] - last[j]).squaredNorm();
      if (o.smoothness == Smoothness::Acceleration && i > 1)
        for (std::size_t j = 0; j < sk.joints.size(); ++j) tm.lsm += (pos[j] - 2 * last[j] + before_last[j]).squaredNorm();
      before_last = last;
      last = pos;
    }
    return tm;
  };
  rep.raw = terms(raw);
  double wsum = 0;
  int fitted = 0;
  for (int i = 0; i < m; ++i)
    if (data[static_cast<std::size_t>(best_first + i)].fit) wsum += weight3d[static_cast<std::size_t>(i)], ++fitted;
  rep.mean_weight_3d = wsum / fitted;

  rep.raw_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  // The reconstruction: every frame together.
  std::vector<std::vector<double>> q = raw;
  FrameKinematics kinematics(g, q);
  ceres::Problem::Options po;
  po.evaluation_callback = &kinematics;
  ceres::Problem problem(po);
  std::vector<std::pair<KeypointCost*, double*>> keypoint_costs;  // owned by the problem
  std::vector<std::pair<RotationPriorCost*, double*>> prior_costs;
  for (int i = 0; i < m; ++i) {
    double* block = q[static_cast<std::size_t>(i)].data();
    problem.AddParameterBlock(block, g.dofs);
    bound_joints(problem, block, sk, g.offsets);
    problem.SetParameterLowerBound(block, 2, kMinDepth);
    const FrameData& d = data[static_cast<std::size_t>(best_first + i)];
    if (d.fit) {
      std::vector<double> scale;
      for (double c : d.confidence) scale.push_back(std::sqrt(2.0 * o.w2d * c));
      auto* kc = new KeypointCost{&g, d.seen, d.target, scale, focal, std::vector<double>(2 * d.seen.size(), 1.0)};
      keypoint_costs.emplace_back(kc, block);
      problem.AddResidualBlock(make_cost(kc, g.dofs, 1, 2 * static_cast<int>(d.seen.size())), nullptr, block);
      const double w = o.w3d * weight3d[static_cast<std::size_t>(i)];
      if (w > 0) {
        auto* rc = new RotationPriorCost{&g, rotating, prior[static_cast<std::size_t>(i)], std::sqrt(2.0 * w), std::vector<double>(rotating.size(), 1.0)};
        prior_costs.emplace_back(rc, block);
        problem.AddResidualBlock(make_cost(rc, g.dofs, 1, 3 * static_cast<int>(rotating.size())), nullptr, block);
      }
    }
    const bool second = o.smoothness == Smoothness::Acceleration;
    if (o.wsm > 0 && i > (second ? 1 : 0)) {
      const double c = std::sqrt(2.0 * o.wsm);
      const auto t = static_cast<std::size_t>(i);
      if (second)
        problem.AddResidualBlock(new SmoothnessCost(kinematics, {t - 2, t - 1, t}, {c, -2 * c, c}, 3 * sk.num_joints(), g.dofs), nullptr,
                                 q[t - 2].data(), q[t - 1].data(), block);
      else
        problem.AddResidualBlock(new SmoothnessCost(kinematics, {t - 1, t}, {c, -c}, 3 * sk.num_joints(), g.dofs), nullptr, q[t - 1].data(), block);
    }
  }
  ceres::Solver::Options so;
  so.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  // Eigen's sparse Cholesky: SuiteSparse's calls a threaded BLAS, which beside the trainers'
  // workers was 7-14 times slower here (and its thread count would change the numbers).
  so.sparse_linear_algebra_library_type = ceres::EIGEN_SPARSE;
  so.max_num_iterations = std::max(1, o.max_iterations / kReweightRounds);
  so.function_tolerance = 1e-5;  // relative; below it the poses move by well under a millimetre
  so.num_threads = 1;
  so.minimizer_progress_to_stdout = o.verbose;
  ceres::Solver::Summary summary;
  for (int round = 0; round < kReweightRounds; ++round) {
    if (round > 0) {  // weights from the last round's residuals (each divided by its weight: the plain one)
      for (auto& [kc, block] : keypoint_costs) {
        std::vector<double> r(kc->reweight.size());
        const double* params[] = {block};
        (*kc)(params, r.data());
        for (std::size_t k = 0; k < r.size(); ++k) {
          const double x = std::abs(r[k]) / (kc->scale[k / 2] * kc->reweight[k]);
          kc->reweight[k] = 1.0 / std::sqrt(std::max(x, kPixelEpsilon));
        }
      }
      for (auto& [rc, block] : prior_costs) {
        std::vector<double> r(3 * rc->reweight.size());
        const double* params[] = {block};
        (*rc)(params, r.data());
        for (std::size_t k = 0; k < rc->reweight.size(); ++k) {
          const double x = Vec3(r[3 * k], r[3 * k + 1], r[3 * k + 2]).norm() / (rc->scale * rc->reweight[k]);
          rc->reweight[k] = 1.0 / std::sqrt(std::max(x, kAngleEpsilon));
        }
      }
    }
    ceres::Solve(so, &problem, &summary);
    if (!summary.IsSolutionUsable()) throw Error(where + ": the reconstruction did not converge: " + summary.message);
    rep.iterations += static_cast<int>(summary.iterations.size());
  }
  rep.reconstructed = terms(q);

  // The ground, and the world's axes in the camera's.
  std::vector<std::vector<Vec3>> cam(static_cast<std::size_t>(m));
  for (int i = 0; i < m; ++i) cam[static_cast<std::size_t>(i)] = positions(g, q[static_cast<std::size_t>(i)]);
  const GroundFit ground = fit_ground(cam);
  rep.ground_fitted = ground.fitted;
  rep.camera_pitch_deg = ground.pitch_deg;
  const Vec3 origin = cam.front()[0] - ground.up * cam.front()[0].dot(ground.up);
  out.reconstructed = to_world(g, ground, origin, q, track.fps, "reconstructed");
  out.raw = to_world(g, ground, origin, raw, track.fps, "raw");
  const double lift = -clip_min_height(out.reconstructed);  // the lowest point on the floor
  for (Clip* c : {&out.reconstructed, &out.raw})
    for (Pose& p : c->frames) p.root_pos.z() += lift;
  rep.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

Pose estimate_frame_pose(const KeypointTrack& track, int frame, const Skeleton& sk, const KeypointMap& map, const ReconstructionOptions& o) {
  track.validate();
  sk.validate();
  const std::string where = track.source.empty() ? std::string("keypoints") : track.source;
  if (frame < 0 || frame >= track.num_frames())
    throw Error(where + ": no frame " + std::to_string(frame) + " (it has " + std::to_string(track.num_frames()) + ", from 0)");
  std::vector<std::string> unused;
  const std::vector<Binding> bindings = bind_keypoints(track, sk, map, where, unused);
  const FrameData d = frame_data(track, frame, bindings, o.min_keypoints);
  if (!d.fit) {
    if (track.frames[static_cast<std::size_t>(frame)].world.empty())
      throw Error(where + ": frame " + std::to_string(frame) + " has no 3D keypoints (\"world\"), which a pose needs" +
                  (track.frames[static_cast<std::size_t>(frame)].empty() ? " (no person was found in it)" : ""));
    throw Error(where + ": frame " + std::to_string(frame) + " has " + std::to_string(d.seen.size()) +
                " keypoints of the character seen, fewer than the " + std::to_string(o.min_keypoints) + " a pose needs");
  }
  Geometry g{&sk, parameter_offsets(sk), sk.dof_count()};
  std::vector<double> p = rest_ahead(g);
  int iterations = 0;
  fit_frame(g, bindings, d, focal_of(track, o), p, iterations);
  const std::vector<Vec3> cam = positions(g, p);
  const GroundFit level = fit_ground({cam});  // one frame shows no floor: a level camera
  const Vec3 origin = cam[0] - level.up * cam[0].dot(level.up);
  Clip c = to_world(g, level, origin, {p}, track.fps, "pose");
  Pose pose = c.frames.front();
  pose.root_pos.z() -= clip_min_height(c);  // the lowest point on the floor
  return pose;
}

}  // namespace mimic
