#include "env/imitation_env.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <span>
#include <utility>

#include "core/error.hpp"

namespace mimic {

InitState place_at_track_start(InitState s) {
  const Quat undo = heading_rotation(-heading_angle(s.pose.rot[0]));
  const Vec3 shift(s.pose.root_pos.x(), s.pose.root_pos.y(), 0.0);
  s.pose.root_pos = Vec3(0, 0, s.pose.root_pos.z());
  s.pose.rot[0] = (undo * s.pose.rot[0]).normalized();
  // Past poses move rigidly with the start, so the history keeps the motion that led to it.
  for (Pose& p : s.past) {
    p.root_pos = undo * (p.root_pos - shift);
    p.rot[0] = (undo * p.rot[0]).normalized();
  }
  // Root velocities are in the world frame; joint velocities are in their own frames and stay.
  s.velocity.root_lin = undo * s.velocity.root_lin;
  s.velocity.root_ang = undo * s.velocity.root_ang;
  // The source clip's root is moved as the start was, after whatever placed it before.
  s.source.turn = (undo * s.source.turn).normalized();
  s.source.offset = undo * (s.source.offset - shift);
  return s;
}

namespace {

// Uniform +-noise on every axis of every non-root joint (revolute angles kept within limits).
void perturb_joints(Pose& p, const Skeleton& sk, double noise, std::mt19937_64& rng) {
  if (noise <= 0) return;
  std::uniform_real_distribution<double> u(-noise, noise);
  for (std::size_t j = 1; j < sk.joints.size(); ++j) {
    const Joint& jt = sk.joints[j];
    if (jt.type == JointType::Spherical) {
      const double x = u(rng), y = u(rng), z = u(rng);
      p.rot[j] = (p.rot[j] * rotvec_to_quat(Vec3(x, y, z))).normalized();
    } else if (jt.type == JointType::Revolute) {
      double angle = revolute_angle(jt, p.rot[j]) + u(rng);
      if (!jt.limits.empty()) angle = std::clamp(angle, jt.limits[0].first, jt.limits[0].second);
      p.rot[j] = Quat(Eigen::AngleAxisd(angle, jt.axis));
    }
  }
}

void check(const ImitationEnvConfig& cfg, const CharacterModel& ch, const std::vector<std::shared_ptr<const Clip>>& clips,
           const std::vector<std::shared_ptr<const Clip>>& start_clips) {
  auto fail = [](const std::string& what) { throw Error("imitation env: " + what); };
  const std::pair<const char*, double> values[] = {
      {"alive_bonus", cfg.alive_bonus},       {"forward_weight", cfg.forward_weight},
      {"target_speed", cfg.target_speed},     {"lateral_weight", cfg.lateral_weight},
      {"control_weight", cfg.control_weight}, {"init_noise", cfg.init_noise}};
  for (const auto& [name, v] : values)
    if (!(v >= 0) || !std::isfinite(v)) fail(std::string(name) + " must be a non-negative number");
  if (!(cfg.goal_speed >= 0) || !(cfg.goal_weight >= 0) || !(cfg.goal_sharpness >= 0) || !(cfg.goal_period > 0) ||
      !std::isfinite(cfg.goal_period))
    fail("goal_speed, goal_weight and goal_sharpness must be non-negative and goal_period positive");
  if (!(cfg.goal_turn >= 0 && cfg.goal_turn <= 180)) fail("goal_turn must be in [0, 180] degrees");
  if (!(cfg.goal_facing >= 0 && cfg.goal_facing <= 1)) fail("goal_facing must be a share in [0, 1]");
  if (!(cfg.fallen_starts >= 0 && cfg.fallen_starts <= 1)) fail("fallen_starts must be a fraction in [0, 1]");
  if (cfg.init == ImitationEnvConfig::Init::Mocap && clips.empty())
    fail("Mocap initialisation needs a motion clip");
  if (!(cfg.start_clip_share >= 0 && cfg.start_clip_share <= 1)) fail("start_clip_share must be a fraction in [0, 1]");
  if (cfg.start_clip_share > 0 && start_clips.empty()) fail("start_clip_share is above 0 but no start clips are given");
  if (cfg.start_clip_share > 0 && cfg.init != ImitationEnvConfig::Init::Mocap) fail("start clips replace mocap starts: they need init: mocap");
  if (cfg.env.max_drift > 0 && cfg.init != ImitationEnvConfig::Init::Mocap)
    throw KeyError("max_drift", "measures against the clip a start was drawn from: it needs mocap starts (init: mocap)");
  // `what`: "clip" or "start clip", for the errors.
  auto check_fit = [&](const std::vector<std::shared_ptr<const Clip>>& list, const std::string& what) {
    for (const auto& clip : list) {
      if (!clip) fail("a " + what + " of the list is missing");
      if (clip->skeleton.num_joints() != ch.skeleton.num_joints())
        fail(what + " '" + clip->name + "' does not fit character '" + ch.name + "'");
      if (!(clip->duration() > 0)) fail(what + " '" + clip->name + "' has no duration to start from");
    }
  };
  check_fit(start_clips, "start clip");
  check_fit(clips, "clip");
}

// A start time uniform over all clips' frames together (seed 004's integrated learning draws
// poses uniformly from the collection), as the clip and the time on it.
std::pair<std::shared_ptr<const Clip>, double> draw_clip_time(std::span<const std::shared_ptr<const Clip>> clips,
                                                              std::mt19937_64& rng) {
  double total = 0;
  for (const auto& c : clips) total += c->duration();
  double t = std::uniform_real_distribution<double>(0.0, total)(rng);
  for (const auto& c : clips) {
    if (t < c->duration()) return {c, t};
    t -= c->duration();
  }
  return {clips.back(), clips.back()->duration()};  // t == total after rounding
}

// CharacterEnv does not keep the action or the root's position before a step: this keeps both
// for the control and forward terms, and the goal's target direction.
class ImitationEnv final : public CharacterEnv {
 public:
  ImitationEnv(const CharacterModel& ch, const ImitationEnvConfig& cfg)
      : CharacterEnv(ch, cfg.env), cfg_(cfg), dt_(1.0 / cfg.env.sim.control_hz) {
    const double dt = dt_;
    add_reward_term("alive", [bonus = cfg.alive_bonus](const CharacterEnv&) { return bonus; });
    if (cfg.goal == ImitationEnvConfig::Goal::Heading) {
      add_reward_term("goal", [this, dt](const CharacterEnv& env) {
        const Vec3 now = env.world().root_position();
        const Eigen::Vector2d d(std::cos(goal_), std::sin(goal_));
        const Eigen::Vector2d v((now.x() - before_.x()) / dt, (now.y() - before_.y()) / dt);
        const double along = d.dot(v), miss = std::max(0.0, cfg_.goal_speed - along), across = (v - along * d).squaredNorm();
        const double moving = along > 0 ? std::exp(-cfg_.goal_sharpness * (miss * miss + 0.1 * across)) : 0.0;
        const double yaw = heading_angle(env.world().pose().rot[0]);
        const double facing = std::max(0.0, std::cos(yaw) * d.x() + std::sin(yaw) * d.y());
        return cfg_.goal_weight * ((1.0 - cfg_.goal_facing) * moving + cfg_.goal_facing * facing);
      });
      add_observation_part("goal", 2, [this](const CharacterEnv&, Eigen::Ref<Eigen::VectorXd> out) { observe_goal(out); });
    } else {
      add_reward_term("forward", [this, dt, w = cfg.forward_weight, target = cfg.target_speed](const CharacterEnv& env) {
        const double vx = (env.world().root_position().x() - before_.x()) / dt;
        return target > 0 ? -w * std::abs(vx - target) : w * vx;
      });
      add_reward_term("lateral", [w = cfg.lateral_weight](const CharacterEnv& env) {
        return -w * std::abs(env.world().root_position().y());
      });
    }
    add_reward_term("control", [this, w = cfg.control_weight](const CharacterEnv&) {
      double sum = 0;
      for (const double a : action_) {
        const double v = std::isfinite(a) ? std::clamp(a, -kPi, kPi) : 0.0;
        sum += v * v;
      }
      return -w * sum;
    });
  }

  using CharacterEnv::reset;
  Eigen::VectorXd reset(std::mt19937_64& rng) override {
    // (No draw that a feature off does not need: runs without it keep their random sequence.)
    if (has_goal()) goal_rng_.seed(rng());
    Eigen::VectorXd observation;
    {
      struct Sampling {  // the target is drawn once, below, where the start has settled
        bool& on;
        explicit Sampling(bool& flag) : on(flag) { on = true; }
        ~Sampling() { on = false; }
      } sampling(sampling_);
      observation = CharacterEnv::reset(rng);
      if (cfg_.fallen_starts > 0 && std::uniform_real_distribution<double>(0.0, 1.0)(rng) < cfg_.fallen_starts)
        observation = fall(rng);  // CharacterEnv::lying_start() says so
    }
    if (has_goal()) {
      draw_goal();  // after the start is placed: a turn is drawn from where the character faces
      observe_goal(observation.tail(2));
    }
    return observation;
  }

  StepResult step(const Eigen::VectorXd& action) override {
    action_ = action;
    before_ = world().root_position();
    StepResult r = CharacterEnv::step(action);
    // A new target after each period: this step was rewarded for the old one, the next observes the new.
    const auto periods = [this](double t) { return std::floor((t + 1e-9) / cfg_.goal_period); };
    if (has_goal() && periods(elapsed()) > periods(elapsed() - dt_)) {
      draw_goal();
      observe_goal(r.observation.tail(2));  // "goal" is the last part
    }
    return r;
  }

  // A start given as a state (a measurement from a clip's phases, a runtime hand-over) draws its
  // target from where it faces, as a sampled start does; without this it kept the last episode's.
  void on_start() override {
    if (has_goal() && !sampling_) draw_goal();
  }

  bool has_goal() const { return cfg_.goal == ImitationEnvConfig::Goal::Heading; }
  Eigen::Vector2d goal_observation() const {
    Eigen::Vector2d out;
    observe_goal(out);
    return out;
  }
  double goal() const { return goal_; }
  void set_goal(double yaw) { goal_ = yaw; }

 private:
  // Any direction (as drawn before goal_turn existed, so such runs keep their sequence), or within
  // goal_turn of where the character faces now (0: straight on), wrapped into [-pi, pi).
  void draw_goal() {
    if (cfg_.goal_turn >= 180.0) {
      goal_ = std::uniform_real_distribution<double>(-kPi, kPi)(goal_rng_);
      return;
    }
    const double turn = cfg_.goal_turn * kPi / 180.0;
    const double yaw = heading_angle(world().pose().rot[0]) + (turn > 0 ? std::uniform_real_distribution<double>(-turn, turn)(goal_rng_) : 0.0);
    goal_ = yaw - 2 * kPi * std::floor((yaw + kPi) / (2 * kPi));
  }
  // The target's cos and sin in the character's heading frame.
  void observe_goal(Eigen::Ref<Eigen::VectorXd> out) const {
    const double relative = goal_ - heading_angle(world().pose().rot[0]);
    out[0] = std::cos(relative), out[1] = std::sin(relative);
  }

  // The start just placed, tumbled to a random orientation 1.2 m up, dropped limp for 1.5 s: the
  // episode starts from where it settled. Drawn from a clip that begins lying (a get-up), the
  // tumble faces the side the clip lies on (its first frame's face up or down: the other side is
  // the other get-up's), and the episode lasts kFallenClips of the clip's duration (a lying start
  // otherwise runs to max_seconds, most of it standing after the get-up).
  Eigen::VectorXd fall(std::mt19937_64& rng) {
    const std::shared_ptr<const Clip> from = start_source().clip;  // the ordinary start's, before it is replaced
    const int side = from && begins_lying(*from) ? lying_side(from->frames.front()) : 0;
    InitState s{world().pose(), PoseVelocity{}, 0.0, {}};
    s.velocity.joint_ang.assign(world().character().skeleton.joints.size(), Vec3::Zero());
    std::normal_distribution<double> gauss(0.0, 1.0);
    const Quat start = s.pose.rot[0];
    // A uniformly random orientation; with a side to keep, drawn again until the forward axis points
    // at least 30 degrees to that side (a quarter of all draws: 64 tries all miss with p < 1e-7).
    for (int tries = 0; tries < 64; ++tries) {
      Quat turn(gauss(rng), gauss(rng), gauss(rng), gauss(rng));
      if (!(turn.norm() > 1e-9)) turn = Quat::Identity();
      s.pose.rot[0] = (turn.normalized() * start).normalized();
      if (side == 0 || side * (s.pose.rot[0] * Vec3::UnitX()).z() > 0.5) break;
    }
    s.pose.root_pos = Vec3(s.pose.root_pos.x(), s.pose.root_pos.y(), 1.2);
    CharacterEnv::reset(s);
    const int settle = static_cast<int>(std::lround(kFallSeconds * cfg_.env.sim.control_hz));
    for (int k = 0; k < settle; ++k) world().step_limp();
    InitState lying{world().pose(), world().velocity(), 0.0, {}};
    lying.lying = true;  // it has fallen already: its contacts end nothing
    if (from && from->loop != LoopMode::Wrap) lying.clip_left = kFallenClips * from->duration();
    return CharacterEnv::reset(lying);
  }
  static constexpr double kFallSeconds = 1.5;
  static constexpr double kFallenClips = 1.5;  // a fallen episode's length in its clip's durations

  ImitationEnvConfig cfg_;
  bool sampling_ = false;          // inside reset(rng): its starts draw no target of their own
  double dt_;
  Eigen::VectorXd action_;
  Vec3 before_ = Vec3::Zero();
  double goal_ = 0.0;
  std::mt19937_64 goal_rng_;
};

}  // namespace

double goal_heading(const CharacterEnv& env) {
  const auto* h = dynamic_cast<const ImitationEnv*>(&env);
  if (!h || !h->has_goal()) throw Error("goal_heading: not an imitation environment with goal: heading");
  return h->goal();
}

void set_goal_heading(CharacterEnv& env, double yaw) {
  auto* h = dynamic_cast<ImitationEnv*>(&env);
  if (!h || !h->has_goal()) throw Error("set_goal_heading: not an imitation environment with goal: heading");
  h->set_goal(yaw);
}

std::unique_ptr<CharacterEnv> make_imitation_env(const CharacterModel& ch,
                                                        std::shared_ptr<const Clip> clip,
                                                        const ImitationEnvConfig& cfg) {
  std::vector<std::shared_ptr<const Clip>> clips;
  if (clip) clips.push_back(std::move(clip));
  return make_imitation_env(ch, std::move(clips), cfg);
}

std::unique_ptr<CharacterEnv> make_imitation_env(const CharacterModel& ch,
                                                        std::vector<std::shared_ptr<const Clip>> clips,
                                                        const ImitationEnvConfig& cfg,
                                                        std::vector<std::shared_ptr<const Clip>> start_clips) {
  check(cfg, ch, clips, start_clips);
  // The clips are not the env's reference: they supply starts (and a non-cyclic one's end), not
  // the phase a reference would (nothing is tracked).
  auto env = std::make_unique<ImitationEnv>(ch, cfg);
  if (cfg.env.allow_clip_contacts)
    for (const auto& clip : clips) env->allow_contacts_of(*clip);
  const Skeleton sk = ch.skeleton;
  const double noise = cfg.init_noise;
  if (cfg.init == ImitationEnvConfig::Init::Mocap) {
    const CharacterEnv* self = env.get();  // the sampler lives in the env it reads
    env->set_start_groups(static_cast<int>(clips.size()));
    const double share = cfg.start_clip_share;
    env->set_init_sampler([clips, start_clips, share, sk, noise, self](std::mt19937_64& rng) {
      const int group = self->start_group();
      const auto [clip, when] = group < 0 ? draw_clip_time(clips, rng) : draw_clip_time(std::span(clips).subspan(static_cast<std::size_t>(group), 1), rng);
      // (Drawn only with a share above 0: runs without start clips keep their random sequence.)
      const bool other = share > 0 && std::uniform_real_distribution<double>(0.0, 1.0)(rng) < share;
      InitState s;
      if (other) {
        const auto [from, at] = draw_clip_time(start_clips, rng);
        s = place_at_track_start(self->state_on_clip(*from, at));  // no source: nothing to drift from
        if (clip->loop != LoopMode::Wrap) s.clip_left = clip->duration();  // one whole kick from wherever it starts
      } else {
        s = self->state_on_clip(*clip, when);
        s.source = StartSource{clip, when};
        s = place_at_track_start(std::move(s));
        if (clip->loop != LoopMode::Wrap) s.clip_left = clip->duration() - when;  // seed 004: a kick ends with its clip
      }
      s.time = 0.0;
      perturb_joints(s.pose, sk, noise, rng);
      return s;
    });
  } else {
    // Standing like CharacterEnv's default start: the lowest body point just above the floor.
    const Vec3 root(0, 0, ch.rest_root_height() + 1e-3);
    env->set_init_sampler([sk, root, noise](std::mt19937_64& rng) {
      InitState s{rest_pose(sk, root), PoseVelocity{}, 0.0, {}};
      s.velocity.joint_ang.assign(sk.joints.size(), Vec3::Zero());
      perturb_joints(s.pose, sk, noise, rng);
      return s;
    });
  }
  return env;
}

bool has_heading_goal(const CharacterEnv& env) {
  const auto* h = dynamic_cast<const ImitationEnv*>(&env);
  return h && h->has_goal();
}

Eigen::Vector2d goal_observation(const CharacterEnv& env) {
  const auto* h = dynamic_cast<const ImitationEnv*>(&env);
  if (!h || !h->has_goal()) throw Error("goal_observation: not an imitation environment with goal: heading");
  return h->goal_observation();
}

}  // namespace mimic
