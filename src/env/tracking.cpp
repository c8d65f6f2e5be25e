#include "env/tracking.hpp"

#include <mujoco/mujoco.h>

#include <cmath>

#include "core/error.hpp"

namespace mimic {

namespace {

// Joints that move: the root and every spherical or revolute joint.
bool tracked(const Joint& j) { return j.type != JointType::Fixed; }

double squared(double x) { return x * x; }

}  // namespace

TrackingTerms tracking_terms(const Skeleton& sk, const TrackedState& sim, const TrackedState& ref, const TrackingScales& scales,
                             ComTerm com) {
  double pose = 0, vel = 0, ee = 0;
  int joints = 0, effectors = 0;
  const HeadingFrame sim_heading = HeadingFrame::of(sim.pose), ref_heading = HeadingFrame::of(ref.pose);
  for (std::size_t j = 0; j < sk.joints.size(); ++j) {
    const Joint& jt = sk.joints[j];
    if (tracked(jt)) {
      ++joints;
      pose += squared(rotation_distance(ref.pose.rot[j], sim.pose.rot[j]));
      const Vec3 w_sim = j == 0 ? sim.velocity.root_ang : sim.velocity.joint_ang[j];
      const Vec3 w_ref = j == 0 ? ref.velocity.root_ang : ref.velocity.joint_ang[j];
      vel += (w_ref - w_sim).squaredNorm();
    }
    if (jt.end_effector) {
      ++effectors;
      const Vec3 p_sim = sim_heading.dir_to_local(sim.links.joint_pos[j] - sim.links.joint_pos[0]);
      const Vec3 p_ref = ref_heading.dir_to_local(ref.links.joint_pos[j] - ref.links.joint_pos[0]);
      ee += (p_ref - p_sim).squaredNorm();
    }
  }
  TrackingTerms t;
  if (joints > 0) {
    t.pose = std::exp(-scales.pose * pose / joints);
    t.velocity = std::exp(-scales.velocity * vel / joints);
  }
  if (effectors > 0) t.end_effector = std::exp(-scales.end_effector * ee / effectors);
  const Vec3 com_error = com == ComTerm::Velocity ? Vec3(ref.com_velocity - sim.com_velocity) : Vec3(ref.com - sim.com);
  t.com = std::exp(-scales.com * com_error.squaredNorm());
  const double root_error = (ref.pose.root_pos - sim.pose.root_pos).squaredNorm() +
                            0.1 * squared(rotation_distance(ref.pose.rot[0], sim.pose.rot[0])) +
                            0.01 * (ref.velocity.root_lin - sim.velocity.root_lin).squaredNorm() +
                            0.001 * (ref.velocity.root_ang - sim.velocity.root_ang).squaredNorm();
  t.root = std::exp(-scales.root * root_error);
  return t;
}

MassModel::MassModel(const World& world) {
  const mjModel* m = world.model();
  const Skeleton& sk = world.character().skeleton;
  for (const Joint& j : sk.joints) {
    const int b = mj_name2id(m, mjOBJ_BODY, j.name.c_str());
    if (b < 0) throw Error("MassModel: the model has no body '" + j.name + "'");
    mass_.push_back(m->body_mass[b]);
    local_com_.emplace_back(m->body_ipos[3 * b], m->body_ipos[3 * b + 1], m->body_ipos[3 * b + 2]);
    total_ += m->body_mass[b];
  }
  if (!(total_ > 0)) throw Error("MassModel: the character has no mass");
}

Vec3 MassModel::centre_of_mass(const LinkFrames& links) const {
  Vec3 sum = Vec3::Zero();
  for (std::size_t j = 0; j < mass_.size(); ++j) sum += mass_[j] * (links.joint_pos[j] + links.joint_rot[j] * local_com_[j]);
  return sum / total_;
}

TrackedState reference_state(const Clip& clip, const MassModel& masses, double t, double dt) {
  TrackedState s;
  std::tie(s.pose, s.velocity) = clip_state(clip, t);
  forward_kinematics(clip.skeleton, s.pose, s.links);
  s.com = masses.centre_of_mass(s.links);
  if (dt > 0) {
    LinkFrames before;
    forward_kinematics(clip.skeleton, clip.sample(t - dt), before);
    s.com_velocity = (s.com - masses.centre_of_mass(before)) / dt;
  }
  return s;
}

namespace {

void check(const TrackingConfig& cfg, const CharacterModel& ch, const Clip* clip) {
  auto fail = [](const std::string& what) { throw Error("tracking: " + what); };
  if (!clip) fail("needs a reference clip");
  if (clip->skeleton.num_joints() != ch.skeleton.num_joints())
    fail("clip '" + clip->name + "' does not fit character '" + ch.name + "' (" + std::to_string(clip->skeleton.num_joints()) +
         " joints, the character has " + std::to_string(ch.skeleton.num_joints()) + ")");
  if (clip->num_frames() < 2) fail("clip '" + clip->name + "' has fewer than 2 frames");
  const std::pair<const char*, double> values[] = {
      {"weights.pose", cfg.weights.pose},       {"weights.velocity", cfg.weights.velocity},
      {"weights.end_effector", cfg.weights.end_effector}, {"weights.com", cfg.weights.com},
      {"weights.root", cfg.weights.root},       {"scales.pose", cfg.scales.pose},
      {"scales.velocity", cfg.scales.velocity}, {"scales.end_effector", cfg.scales.end_effector},
      {"scales.com", cfg.scales.com},           {"scales.root", cfg.scales.root}};
  for (const auto& [name, v] : values)
    if (!(v >= 0) || !std::isfinite(v)) fail(std::string(name) + " must be a non-negative number");
}

// Moves a reference state by `d` (the root, every link and the centre of mass).
void shift(TrackedState& s, const Vec3& d) {
  s.pose.root_pos += d;
  for (Vec3& p : s.links.joint_pos) p += d;
  s.com += d;
}

// Appends the weighted terms after each step, against the reference at the step's time.
class TrackingEnv final : public CharacterEnv {
 public:
  TrackingEnv(const CharacterModel& ch, std::shared_ptr<const Clip> clip, const TrackingConfig& cfg)
      : CharacterEnv(ch, cfg.env, std::move(clip)), masses_(world()), weights_(cfg.weights), scales_(cfg.scales),
        com_term_(cfg.com_term), resync_(cfg.resync_root && reference()->loop == LoopMode::Wrap),
        dt_(1.0 / cfg.env.sim.control_hz) {
    set_max_step_reward(weights_.pose + weights_.velocity + weights_.end_effector + weights_.com + weights_.root);
  }

  StepResult step(const Eigen::VectorXd& action) override {
    const bool by_velocity = com_term_ == ComTerm::Velocity;
    const Vec3 com_before = by_velocity ? world().centre_of_mass() : Vec3::Zero();
    StepResult r = CharacterEnv::step(action);
    const World& w = world();
    sim_.pose = w.pose();
    sim_.velocity = w.velocity();
    sim_.links = w.link_frames();
    sim_.com = w.centre_of_mass();
    if (by_velocity) sim_.com_velocity = (sim_.com - com_before) / dt_;
    TrackedState ref = reference_state(*reference(), masses_, time(), by_velocity ? dt_ : 0.0);
    if (resync_) {
      const auto cycle = static_cast<long long>(std::floor(time() / reference()->duration()));
      if (cycle != cycle_) {  // a new cycle: the reference's root onto the character's, horizontally
        cycle_ = cycle;
        offset_ = sim_.pose.root_pos - ref.pose.root_pos;
        offset_.z() = 0;
      }
      shift(ref, offset_);
    }
    const TrackingTerms t = tracking_terms(w.character().skeleton, sim_, ref, scales_, com_term_);
    r.reward_terms.emplace_back("pose", weights_.pose * t.pose);
    r.reward_terms.emplace_back("velocity", weights_.velocity * t.velocity);
    r.reward_terms.emplace_back("end_effector", weights_.end_effector * t.end_effector);
    r.reward_terms.emplace_back("com", weights_.com * t.com);
    if (weights_.root > 0) r.reward_terms.emplace_back("root", weights_.root * t.root);
    return r;
  }

 protected:
  void on_start() override {
    offset_ = Vec3::Zero();
    cycle_ = static_cast<long long>(std::floor(time() / reference()->duration()));
  }

 private:
  MassModel masses_;
  TrackingWeights weights_;
  TrackingScales scales_;
  ComTerm com_term_;
  bool resync_;       // resync_root on a looping clip
  double dt_;         // control step
  Vec3 offset_ = Vec3::Zero();
  long long cycle_ = 0;  // the reference's cycle the offset was taken at
  TrackedState sim_;  // storage reused every step
};

}  // namespace

std::unique_ptr<CharacterEnv> make_tracking_env(const CharacterModel& ch, std::shared_ptr<const Clip> clip,
                                                const TrackingConfig& cfg) {
  check(cfg, ch, clip.get());
  auto env = std::make_unique<TrackingEnv>(ch, clip, cfg);
  if (cfg.init == TrackingConfig::Init::Reference) {
    env->set_init_sampler([clip](std::mt19937_64& rng) {
      std::uniform_real_distribution<double> when(0.0, clip->duration());
      return init_state_from_clip(*clip, when(rng));
    });
  }  // Fixed: CharacterEnv's default start, the clip's first frame
  return env;
}

}  // namespace mimic
