#include "env/character_env.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "motion/kinematics.hpp"

namespace mimic {

InitState init_state_from_clip(const Clip& clip, double t, int past, double dt) {
  auto [pose, vel] = clip_state(clip, t);
  InitState s{std::move(pose), std::move(vel), t, {}};
  for (int k = past; k >= 1; --k) s.past.push_back(clip.sample(t - k * dt));
  return s;
}

void smooth_start_momentum(const World& world, const Clip& clip, double t, const StartMomentumSmoothing& smoothing,
                           InitState& s) {
  if (!(smoothing.window > 0)) throw Error("start momentum window must be positive seconds");
  constexpr int kSide = 8;  // states each side of t
  constexpr int kStates = 2 * kSide + 1;
  using States = Eigen::Matrix<double, 3, kStates>;  // one column per state
  States linears, angulars;
  for (int k = -kSide; k <= kSide; ++k) {
    const auto [pose, vel] = clip_state(clip, t + smoothing.window * k / kSide);
    const BodyMomentum m = world.momentum_of(pose, vel);
    linears.col(k + kSide) = m.com_velocity;
    angulars.col(k + kSide) = m.angular;
  }
  auto summary = [&](const States& v) -> Vec3 {
    if (smoothing.statistic == StartMomentumSmoothing::Statistic::Mean) return v.rowwise().mean();
    Vec3 out;
    for (int c = 0; c < 3; ++c) {
      Eigen::Matrix<double, 1, kStates> row = v.row(c);
      std::nth_element(row.data(), row.data() + kSide, row.data() + kStates);
      out[c] = row[kSide];
    }
    return out;
  };
  const Vec3 angular = summary(angulars);
  const BodyMomentum now = world.momentum_of(s.pose, s.velocity);
  // A spin w of the whole body about its centre of mass adds inertia * w to the angular momentum
  // about it and moves every point, the root too, by w x (point - com); the com does not move.
  const Vec3 spin = now.inertia.ldlt().solve(angular - now.angular);
  s.velocity.root_ang += spin;
  s.velocity.root_lin += spin.cross(s.pose.root_pos - now.com);
  if (!smoothing.linear) return;
  const Vec3 linear = summary(linears);
  s.velocity.root_lin.x() += linear.x() - now.com_velocity.x();
  s.velocity.root_lin.y() += linear.y() - now.com_velocity.y();
}

namespace {

Pose raised(Pose p, double dz) {
  p.root_pos.z() += dz;
  return p;
}

// The character's model plus the terrain's ground and the projectile pool.
MjcfOptions model_options(const Terrain& terrain, const CharacterEnvConfig& cfg) {
  MjcfOptions opts;
  terrain.add_to(opts);
  ProjectileLauncher::add_to(opts, cfg.projectiles, cfg.sim.control_hz);
  if (cfg.terrain.kind != TerrainKind::Flat) {
    // Height fields make more contacts (at most 29 measured in the terrain tests, where nconmax 200
    // once overflowed); the cube pool adds its own room.
    opts.max_contacts += 300;
    opts.max_constraints += 1000;
  }
  return opts;
}

// The terrain and the pushes, their errors named by their config keys.
Terrain make_terrain(const TerrainSpec& spec) {
  try {
    return Terrain(spec);
  } catch (const Error& e) {
    throw KeyError("terrain", e.what());
  }
}

Pusher make_pusher(const World& world, const std::vector<PushSpec>& pushes) {
  try {
    return Pusher(world, pushes);
  } catch (const Error& e) {
    throw KeyError("pushes", e.what());
  }
}

// What the constructor's members do not check themselves.
void check(const CharacterEnvConfig& cfg) {
  if (!(cfg.max_seconds > 0) || !std::isfinite(cfg.max_seconds)) throw KeyError("max_seconds", "must be positive seconds");
  if (!(cfg.max_drift >= 0) || !std::isfinite(cfg.max_drift)) throw KeyError("max_drift", "must be non-negative metres (0: off)");
  if (!(cfg.fall_height >= 0) || !(cfg.fall_height <= 1)) throw KeyError("fall_height", "must be a fraction in [0, 1] (0: off)");
  if (!(cfg.start_momentum.window >= 0) || !std::isfinite(cfg.start_momentum.window))
    throw KeyError("start_momentum_window", "must be non-negative seconds (0: off)");
}

}  // namespace

CharacterEnv::CharacterEnv(const CharacterModel& ch, const CharacterEnvConfig& cfg, std::shared_ptr<const Clip> reference)
    : cfg_((check(cfg), cfg)),
      terrain_(make_terrain(cfg.terrain)),
      world_(ch, cfg.sim, model_options(terrain_, cfg)),
      reference_(std::move(reference)),
      obs_(world_, cfg.observations, reference_ != nullptr),
      pusher_(make_pusher(world_, cfg.pushes)) {
  terrain_.install(world_.model());
  if (cfg.terrain.levels > 0) terrain_.set_level(1, world_.model());
  if (cfg.projectiles.enabled) launcher_ = std::make_unique<ProjectileLauncher>(world_, cfg.projectiles);
  const Skeleton& sk = ch.skeleton;
  if (reference_ && reference_->skeleton.num_joints() != sk.num_joints())
    throw Error("reference clip '" + reference_->name + "' does not fit character '" + ch.name + "'");
  if (cfg.fall_height > 0 && !reference_)
    throw KeyError("fall_height", "is a fraction of the reference clip's root height: this environment tracks no reference (0: off)");
  for (const Joint& j : sk.joints) {
    if (j.type == JointType::Spherical) action_size_ += cfg.action_mode == ActionMode::AxisAngle ? 3 : 4;
    if (j.type == JointType::Revolute) action_size_ += 1;
  }
  if (cfg.fall_links.empty()) {
    for (std::size_t j = 0; j < ch.bodies.size(); ++j)
      if (ch.bodies[j].fall_contact) fall_joints_.push_back(static_cast<int>(j));
  } else if (cfg.fall_links == std::vector<std::string>{kAllFallLinks}) {
    if (!cfg.allow_clip_contacts && cfg.early_termination)
      throw KeyError("fall_links", "all: every body, the feet too, so every step would fall; set allow_clip_contacts: true (the bodies "
                                   "the clip rests on the ground, a walk's feet, are then no falls) or list the bodies");
    for (std::size_t j = 0; j < sk.joints.size(); ++j) fall_joints_.push_back(static_cast<int>(j));
  } else {
    for (const std::string& name : cfg.fall_links) {
      const int j = sk.find(name);
      if (j < 0) throw KeyError("fall_links", "names '" + name + "', a body character '" + ch.name + "' does not have");
      fall_joints_.push_back(j);
    }
  }
  if (cfg.allow_clip_contacts && reference_) allow_contacts_of(*reference_);
}

void CharacterEnv::allow_contacts_of(const Clip& clip) {
  const CharacterModel& ch = world_.character();
  if (clip.skeleton.num_joints() != ch.skeleton.num_joints())
    throw Error("clip '" + clip.name + "' does not fit character '" + ch.name + "'");
  // Frames each body rests on the ground: near it, with its joint low (a shin beside a planted
  // foot comes as near in a run, its knee high above). Resting takes kClipContactSeconds in all.
  const double low = kClipContactJointHeight * ch.rest_root_height();
  std::vector<int> resting(clip.skeleton.joints.size(), 0);
  LinkFrames links;
  for (const Pose& p : clip.frames) {
    const std::vector<bool> near = world_.ground_contacts_of(p, kClipContactGap);
    forward_kinematics(clip.skeleton, p, links);
    for (std::size_t j = 0; j < near.size(); ++j) resting[j] += near[j] && links.joint_pos[j].z() < low ? 1 : 0;
  }
  const double needed = kClipContactSeconds * clip.fps;
  std::erase_if(fall_joints_, [&](int j) { return resting[static_cast<std::size_t>(j)] >= needed; });
}

std::vector<std::string> CharacterEnv::fall_bodies() const {
  std::vector<std::string> names;
  for (const int j : fall_joints_) names.push_back(world_.character().skeleton.joints[static_cast<std::size_t>(j)].name);
  return names;
}

void CharacterEnv::set_pushes(std::vector<PushSpec> pushes) {
  Pusher next(world_, pushes);
  pusher_.clear(world_);  // no force of the old pushes may stay behind
  pusher_ = std::move(next);
  cfg_.pushes = std::move(pushes);
}

Pose CharacterEnv::targets_from_action(const Eigen::VectorXd& a) const {
  if (a.size() != action_size_)
    throw Error("action has " + std::to_string(a.size()) + " values, the character takes " + std::to_string(action_size_));
  const Skeleton& sk = world_.character().skeleton;
  Pose t = rest_pose(sk);
  Eigen::Index k = 0;
  auto clipped = [&](Eigen::Index i) { return std::isfinite(a[i]) ? std::clamp(a[i], -kPi, kPi) : 0.0; };
  for (std::size_t j = 1; j < sk.joints.size(); ++j) {
    const Joint& jt = sk.joints[j];
    if (jt.type == JointType::Spherical) {
      if (cfg_.action_mode == ActionMode::AxisAngle) {
        t.rot[j] = rotvec_to_quat(Vec3(clipped(k), clipped(k + 1), clipped(k + 2)));
        k += 3;
      } else {
        Quat q(clipped(k), clipped(k + 1), clipped(k + 2), clipped(k + 3));
        t.rot[j] = q.norm() > 1e-9 ? q.normalized() : Quat::Identity();
        k += 4;
      }
    } else if (jt.type == JointType::Revolute) {
      double angle = clipped(k++);
      if (!jt.limits.empty()) angle = std::clamp(angle, jt.limits[0].first, jt.limits[0].second);
      t.rot[j] = Quat(Eigen::AngleAxisd(angle, jt.axis));
    }
  }
  return t;
}

Eigen::VectorXd CharacterEnv::action_for(const Pose& targets) const {
  const Skeleton& sk = world_.character().skeleton;
  if (targets.rot.size() != sk.joints.size()) throw Error("action_for: the pose has the wrong number of joints");
  Eigen::VectorXd a(action_size_);
  Eigen::Index k = 0;
  for (std::size_t j = 1; j < sk.joints.size(); ++j) {
    const Joint& jt = sk.joints[j];
    const Quat& q = targets.rot[j];
    if (jt.type == JointType::Spherical) {
      if (cfg_.action_mode == ActionMode::AxisAngle) {
        a.segment<3>(k) = quat_to_rotvec(q);
        k += 3;
      } else {
        a.segment<4>(k) << q.w(), q.x(), q.y(), q.z();
        k += 4;
      }
    } else if (jt.type == JointType::Revolute) {
      a[k++] = revolute_angle(jt, q);
    }
  }
  return a;
}

void CharacterEnv::choose_start_group(int g) {
  if (g < -1 || g >= start_groups_)
    throw Error("start group " + std::to_string(g) + " is outside [-1, " + std::to_string(start_groups_) + ")");
  start_group_ = g;
}

Eigen::VectorXd CharacterEnv::reset(std::mt19937_64& rng) {
  if (cfg_.terrain.redraw) terrain_.redraw(rng(), world_.model());  // a new course (walls) every episode
  InitState s;
  if (init_sampler_) {
    s = init_sampler_(rng);
  } else if (reference_) {
    s = init_state_from_clip(*reference_, 0.0);
  } else {
    // Standing: the rest pose with the lowest body point on the floor (every terrain is flat at
    // the origin).
    const CharacterModel& ch = world_.character();
    s = InitState{rest_pose(ch.skeleton, Vec3(0, 0, ch.rest_root_height() + 1e-3)), PoseVelocity{}, 0.0, {}};
    s.velocity.joint_ang.assign(ch.skeleton.joints.size(), Vec3::Zero());
  }
  if (launcher_) launcher_->reseed(rng());
  return reset(s);
}

void CharacterEnv::update_terrain_level() {
  if (cfg_.terrain.levels == 0 || starts_ == 0) return;
  const double end = terrain_.course_end(), middle = (terrain_.spec().start_zone + end) / 2;
  int level = terrain_.level();
  if (farthest_x_ >= end + kCurriculumMargin) level = std::min(level + 1, cfg_.terrain.levels);
  else if (episode_failed_ && farthest_x_ < middle) level = std::max(level - 1, 1);
  if (level != terrain_.level()) terrain_.set_level(level, world_.model());
}

Eigen::VectorXd CharacterEnv::reset(const InitState& init) {
  update_terrain_level();
  ++starts_;
  time_ = init.time;
  elapsed_ = 0.0;
  clip_left_ = init.clip_left;
  lying_ = init.lying;
  source_ = init.source;
  history_.clear();
  // Past poses are placed kinematically only to read their link frames, before the real start.
  const auto keep = static_cast<std::size_t>(obs_.link_history() - 1);
  const std::size_t first = init.past.size() > keep ? init.past.size() - keep : 0;
  const double lift = start_lift(init.pose);
  for (std::size_t k = first; k < init.past.size(); ++k) {
    world_.set_state(raised(init.past[k], lift));
    history_.push_back(world_.link_frames());
  }
  world_.set_state(raised(init.pose, lift), &init.velocity);
  world_.set_pd_targets(init.pose);
  if (launcher_) launcher_->reset(world_);
  history_.push_back(world_.link_frames());
  farthest_x_ = world_.root_position().x();
  episode_failed_ = false;
  on_start();
  return observe();
}

double CharacterEnv::start_lift(const Pose& pose) {
  if (!cfg_.lift_starts) return 0.0;
  world_.set_state(pose);
  const double depth = world_.ground_penetration();
  return depth > 0 ? depth + kStartLiftPad : 0.0;
}

InitState CharacterEnv::state_on_clip(const Clip& clip, double t) const {
  InitState s = init_state_from_clip(clip, t, obs_.link_history() - 1, 1.0 / cfg_.sim.control_hz);
  if (cfg_.start_momentum.window > 0) smooth_start_momentum(world_, clip, t, cfg_.start_momentum, s);
  return s;
}

std::vector<ObservationSlice> CharacterEnv::observation_layout() const {
  std::vector<ObservationSlice> layout = obs_.layout();
  int offset = obs_.size();
  for (const ExtraPart& p : extra_) layout.push_back(ObservationSlice{p.name, offset, p.size}), offset += p.size;
  return layout;
}

void CharacterEnv::add_observation_part(std::string name, int size, ObservationPart fill) {
  if (size < 1) throw Error("observation part '" + name + "' must have at least one value");
  for (const ObservationSlice& s : observation_layout())
    if (s.name == name) throw Error("observation part '" + name + "' is already in the observation");
  extra_.push_back(ExtraPart{std::move(name), size, std::move(fill)});
  extra_size_ += size;
}

Eigen::VectorXd CharacterEnv::observe() {
  Eigen::VectorXd named;
  obs_.build(ObservationContext{&world_, &history_, reference_.get(), time_, &terrain_}, named);
  if (extra_.empty()) return named;
  Eigen::VectorXd out(observation_size());
  out.head(named.size()) = named;
  Eigen::Index at = named.size();
  for (const ExtraPart& p : extra_) p.fill(*this, out.segment(at, p.size)), at += p.size;
  return out;
}

bool CharacterEnv::fall_contact() const {
  if (fall_joints_.empty()) return false;
  const std::vector<bool> contact = world_.ground_contacts();
  for (int j : fall_joints_)
    if (contact[static_cast<std::size_t>(j)]) return true;
  return false;
}

bool CharacterEnv::below_reference() const {
  if (!reference_ || !(cfg_.fall_height > 0)) return false;
  return world_.root_position().z() < cfg_.fall_height * reference_->sample(time_).root_pos.z();
}

double CharacterEnv::drift() const {
  if (reference_) return (world_.root_position() - reference_->sample(time_).root_pos).head<2>().norm();
  if (!source_.clip) return 0.0;
  const Vec3 there = source_.place(source_.clip->sample(source_.time + elapsed_).root_pos);
  return (world_.root_position() - there).head<2>().norm();
}

std::optional<Pose> CharacterEnv::reference_pose() const {
  if (reference_) return reference_->sample(time_);
  if (!source_.clip) return std::nullopt;
  Pose p = source_.clip->sample(source_.time + elapsed_);
  p.root_pos = source_.place(p.root_pos);
  p.rot[0] = (source_.turn * p.rot[0]).normalized();
  return p;
}

Termination CharacterEnv::check_termination() const {
  if (cfg_.early_termination && !lying_ && (fall_contact() || below_reference())) return Termination::Fall;
  if (cfg_.max_drift > 0 && drift() > cfg_.max_drift) return Termination::Drift;
  if (reference_ && reference_->loop != LoopMode::Wrap && time_ >= reference_->duration() - 1e-9) return Termination::ClipEnd;
  if (elapsed_ >= clip_left_ - 1e-9) return Termination::ClipEnd;
  if (elapsed_ >= cfg_.max_seconds - 1e-9) return Termination::TimeLimit;
  return Termination::None;
}

StepResult CharacterEnv::step(const Eigen::VectorXd& action) {
  world_.set_pd_targets(targets_from_action(action));
  const double dt = 1.0 / cfg_.sim.control_hz;
  pusher_.apply(world_, elapsed_, dt);
  if (launcher_) launcher_->before_step(world_);
  world_.step();
  if (launcher_) launcher_->after_step(world_);
  time_ += dt;
  elapsed_ += dt;
  history_.push_back(world_.link_frames());
  while (static_cast<int>(history_.size()) > obs_.link_history()) history_.pop_front();
  StepResult r;
  r.observation = observe();
  for (const auto& [name, term] : rewards_) r.reward_terms.emplace_back(name, term(*this));
  r.termination = check_termination();
  farthest_x_ = std::max(farthest_x_, world_.root_position().x());
  episode_failed_ = is_failure(r.termination);
  if (cfg_.terrain.levels > 0) r.info.emplace_back("terrain_level", terrain_.level());
  return r;
}

}  // namespace mimic
