#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <functional>
#include <limits>
#include <random>
#include <tuple>

#include "control/controller_internals.hpp"
#include "control/pose_matching.hpp"
#include "control/skill_impl.hpp"
#include "core/error.hpp"
#include "env/character_env.hpp"
#include "env/context_env.hpp"
#include "env/imitation_env.hpp"
#include "motion/clip.hpp"

namespace mimic {

namespace {

const char* ending_name(Termination t) {
  switch (t) {
    case Termination::Fall: return "fall";
    case Termination::TimeLimit: return "time limit";
    case Termination::ClipEnd: return "clip end";
    case Termination::Drift: return "drift";
    case Termination::None: break;
  }
  return "";
}

}  // namespace

// How many of the character's last states are kept for a hand-over: the link history an
// environment observes (env.link_history) reads at most this many.
constexpr std::size_t kKeptStates = 16;

struct Controller::Impl {
  std::vector<std::shared_ptr<const Skill>> skills;
  std::vector<std::unique_ptr<Env>> envs;  // one per skill: its own observation and action mapping
  std::size_t active = 0;
  std::mt19937_64 rng;
  std::deque<Eigen::VectorXd> frames;  // the active skill's last `history` observations, oldest first
  Eigen::VectorXd input, action;
  long long steps = 0;
  double dt = 0.0;  // control step, seconds
  // The character's last states, oldest first, the newest the current one: MuJoCo's qpos and qvel
  // of the environment they were read from (a copy each step; poses are made only when needed).
  struct RawState {
    std::size_t env = 0;
    std::vector<double> qpos, qvel;
  };
  std::deque<RawState> states;
  SwitchRule rule;
  std::size_t pending = 0;  // the requested skill; == skills.size(): none
  long long waited = 0;     // steps since the request
  int delay_left = 0;       // steps before a request may be granted
  Eigen::Vector3d push_force = Eigen::Vector3d::Zero();
  double push_left = 0.0;   // seconds of the push still to come
  bool pushing = false;     // the active environment holds a push of ours
  double heading = std::nan("");  // the commanded world yaw (set_heading); NaN: none
  std::vector<int> goal_offsets;  // per skill: where its observation's "goal" part is; -1 for a skill without the goal

  // The commanded heading as the active skill's target, its newest frame showing it (the
  // environment's own redraws are overridden step by step). Nothing for a skill without the goal.
  void apply_heading() {
    const int offset = goal_offsets[active];
    if (std::isnan(heading) || offset < 0) return;
    CharacterEnv& character = *character_of(env());
    set_goal_heading(character, heading);
    frames.back().segment(offset, 2) = goal_observation(character);
  }

  Env& env() { return *envs[active]; }
  const Skill& skill() const { return *skills[active]; }
  void begin(const Eigen::VectorXd& first) {
    frames.assign(static_cast<std::size_t>(skill().history()), first);
    steps = 0;
  }
  std::size_t index_of(const std::string& name) const {
    std::string names;
    for (std::size_t i = 0; i < skills.size(); ++i) {
      if (skills[i]->name() == name) return i;
      names += (i ? ", " : "") + skills[i]->name();
    }
    throw Error("no skill '" + name + "' in this controller (it has " + names + ")");
  }
  // Keeps the active world's state (after a reset or a step) for hand-overs and scores.
  void remember() {
    if (skills.size() < 2) return;  // nothing to hand over to: a lone skill's steps keep nothing
    const mjModel* m = env().physics_model();
    const mjData* d = env().physics_data();
    if (!m || !d || !character_of(env())) return;
    RawState s = states.size() >= kKeptStates ? std::move(states.front()) : RawState{};
    if (states.size() >= kKeptStates) states.pop_front();
    s.env = active;
    s.qpos.assign(d->qpos, d->qpos + m->nq);
    s.qvel.assign(d->qvel, d->qvel + m->nv);
    states.push_back(std::move(s));
  }
  // A kept state as the character's pose and velocities, read through the world it came from
  // (its MuJoCo state written in for the reading, then put back).
  std::pair<Pose, PoseVelocity> decode(const RawState& s) {
    CharacterEnv* c = character_of(*envs[s.env]);
    mjData* d = envs[s.env]->physics_data();
    const mjModel* m = envs[s.env]->physics_model();
    const std::vector<double> qpos(d->qpos, d->qpos + m->nq), qvel(d->qvel, d->qvel + m->nv);
    std::copy(s.qpos.begin(), s.qpos.end(), d->qpos);
    std::copy(s.qvel.begin(), s.qvel.end(), d->qvel);
    std::pair<Pose, PoseVelocity> out(c->world().pose(), c->world().velocity());
    std::copy(qpos.begin(), qpos.end(), d->qpos);
    std::copy(qvel.begin(), qvel.end(), d->qvel);
    return out;
  }
  // Skill `target`'s environment put in the character's state `back` states ago, with the states
  // before it as its past; returns that environment's observation.
  Eigen::VectorXd place(std::size_t target, std::size_t back) {
    CharacterEnv* from = character_of(env());
    CharacterEnv* to = character_of(*envs[target]);
    if (!from || !to) throw Error("skill '" + skills[target]->name() + "': only character environments hand a character over");
    if (states.size() <= back) throw Error("skill '" + skills[target]->name() + "': the character has no state " + std::to_string(back) + " steps ago");
    InitState state;
    const std::size_t at = states.size() - 1 - back;
    std::tie(state.pose, state.velocity) = decode(states[at]);
    state.time = from->time() - static_cast<double>(back) * dt;
    for (std::size_t k = 0; k < at; ++k) state.past.push_back(decode(states[k]).first);
    return to->reset(state);
  }
  void hand_over(std::size_t target) {
    if (pushing) {  // the push goes on in the new world; none of it stays in the old
      if (CharacterEnv* c = character_of(env())) c->set_pushes(c->config().pushes);
      pushing = false;
    }
    const Eigen::VectorXd first = place(target, 0);
    const long long kept = steps;
    active = target;
    begin(first);
    steps = kept;
  }
  // The rule's figure for `target` in the current state.
  double measure(std::size_t target, SwitchRule::By by);
  // Skill `target`'s clips as a pose matcher (made on first use, from the clips its starts are
  // drawn from: every start group's, or its tracking reference).
  std::vector<std::unique_ptr<PoseMatcher>> matchers;
  const PoseMatcher& matcher(std::size_t target);

  // Before a step: the push's part of it on the active character's root, beside its own pushes.
  void apply_push() {
    CharacterEnv* c = character_of(env());
    if (!c) return;
    std::vector<PushSpec> pushes = c->config().pushes;
    if (push_left > 0) pushes.push_back(PushSpec{c->world().character().skeleton.joints.front().name, push_force, c->elapsed(), std::min(push_left, dt)});
    if (push_left > 0 || pushing) c->set_pushes(std::move(pushes));
    pushing = push_left > 0;
    push_left = std::max(0.0, push_left - dt);
  }

  // A new episode of skill `target`, made active: the push under way dropped, `first` resetting
  // its environment, no state kept from before and no request pending.
  void new_episode(std::size_t target, const std::function<Eigen::VectorXd(Env&)>& first) {
    push_left = 0.0;
    if (pushing)
      if (CharacterEnv* c = character_of(env())) c->set_pushes(c->config().pushes);
    pushing = false;
    active = target;
    begin(first(env()));
    states.clear();
    remember();
    pending = skills.size();
    delay_left = 0;
  }

  void stack() {
    const Skill& s = skill();
    input.resize(s.input_size());
    for (int f = 0; f < s.history(); ++f) input.segment(f * s.frame_size(), s.frame_size()) = frames[static_cast<std::size_t>(f)];
  }
};

Controller::Controller(std::vector<std::shared_ptr<const Skill>> skills, std::uint64_t seed) : impl_(std::make_unique<Impl>()) {
  if (skills.empty()) throw Error("a controller needs at least one skill");
  impl_->rng.seed(seed);
  const Skill& first = *skills.front();
  for (const auto& s : skills) {
    if (!s) throw Error("a controller's skill is null");
    if (s->impl().bodies != first.impl().bodies || s->action_size() != first.action_size())
      throw Error("skill '" + s->name() + "' (" + s->directory().string() + ") acts on another character than skill '" + first.name() + "' (" +
                  std::to_string(s->impl().bodies.size()) + " bodies and " + std::to_string(s->action_size()) + " actions against " +
                  std::to_string(first.impl().bodies.size()) + " and " + std::to_string(first.action_size()) +
                  "): one controller drives one character");
    for (const auto& other : impl_->skills)
      if (other->name() == s->name()) throw Error("two skills are named '" + s->name() + "': give them names (Skill::load's second argument)");
    impl_->envs.push_back(s->impl().factory());
    impl_->skills.push_back(s);
    int goal = -1;  // a skill trained with a heading goal: where its observation shows it
    CharacterEnv* character = character_of(*impl_->envs.back());
    if (character && has_heading_goal(*character))
      for (const ObservationSlice& part : impl_->envs.back()->observation_layout())
        if (part.name == "goal") goal = part.offset;
    impl_->goal_offsets.push_back(goal);
  }
  impl_->dt = impl_->envs.front()->control_dt();
  if (!(impl_->dt > 0))
    throw Error("skill '" + impl_->skills.front()->name() + "' (" + impl_->skills.front()->directory().string() +
                "): its environment does not say its control step");
  reset();
}

Controller::~Controller() = default;

void Controller::reset() {
  Impl& c = *impl_;
  c.new_episode(c.active, [&](Env& env) { return env.reset(c.rng); });
}

void Controller::start(const std::string& name, const Eigen::VectorXd& qpos, const Eigen::VectorXd& qvel, const std::vector<Eigen::VectorXd>& past,
                       double clip_time) {
  Impl& c = *impl_;
  const std::size_t target = c.index_of(name);
  Env& env = *c.envs[target];
  CharacterEnv* character = character_of(env);
  if (!character) throw Error("start: skill '" + name + "' drives no character");
  const mjModel* m = env.physics_model();
  mjData* d = env.physics_data();
  auto check = [&](const Eigen::VectorXd& v, int size, const std::string& what) {
    if (v.size() != size) throw Error("start: skill '" + name + "': " + what + " has " + std::to_string(v.size()) + " numbers; its character's has " + std::to_string(size));
    if (!v.allFinite()) throw Error("start: skill '" + name + "': " + what + " has a number that is not finite");
  };
  auto check_rotations = [&](const Eigen::VectorXd& q, const std::string& what) {
    for (int j = 0; j < m->njnt; ++j) {
      const int type = m->jnt_type[j];
      if (type != mjJNT_FREE && type != mjJNT_BALL) continue;
      const int a = m->jnt_qposadr[j] + (type == mjJNT_FREE ? 3 : 0);
      if (q.segment(a, 4).norm() < 1e-9) throw Error("start: skill '" + name + "': " + what + " holds a zero quaternion (at " + std::to_string(a) + ")");
    }
  };
  check(qpos, m->nq, "qpos");
  check_rotations(qpos, "qpos");
  check(qvel, m->nv, "qvel");
  for (std::size_t k = 0; k < past.size(); ++k) {
    check(past[k], m->nq, "past qpos " + std::to_string(k));
    check_rotations(past[k], "past qpos " + std::to_string(k));
  }
  if (!std::isfinite(clip_time)) throw Error("start: skill '" + name + "': the clip time is not finite");
  // The state read as the character's pose and velocities through its world.
  auto read = [&](const Eigen::VectorXd& q, const Eigen::VectorXd* v) {
    std::copy(q.data(), q.data() + m->nq, d->qpos);
    if (v) std::copy(v->data(), v->data() + m->nv, d->qvel);
    else std::fill(d->qvel, d->qvel + m->nv, 0.0);
    return std::make_pair(character->world().pose(), character->world().velocity());
  };
  InitState state;
  for (const Eigen::VectorXd& q : past) state.past.push_back(read(q, nullptr).first);
  std::tie(state.pose, state.velocity) = read(qpos, &qvel);
  state.time = clip_time;
  c.new_episode(target, [&](Env&) { return character->reset(state); });
}

StepInfo Controller::step() {
  Impl& c = *impl_;
  c.apply_heading();
  c.stack();
  c.action = c.skill().act(c.input);
  c.apply_push();
  const StepResult r = c.env().step(c.action);
  ++c.steps;
  c.frames.pop_front();
  c.frames.push_back(r.observation);
  c.remember();
  StepInfo info;
  info.episode_over = r.done();
  info.fell = is_failure(r.termination);
  info.ending = ending_name(r.termination);
  if (const CharacterEnv* character = character_of(c.env())) info.ground_contact = character->fall_contact();
  if (c.delay_left > 0) --c.delay_left;
  if (c.pending < c.skills.size()) {
    ++c.waited;
    const std::size_t target = c.pending;
    if (c.delay_left == 0) {
      const bool now = c.rule.by == SwitchRule::By::Immediately;
      if (!now) info.target_score = c.measure(target, c.rule.by);
      if (now || info.target_score >= c.rule.threshold) {
        c.hand_over(target);
        c.pending = c.skills.size();
        c.delay_left = c.rule.delay_steps;
        info.switched_to = c.skill().name();
        return info;
      }
    }
    if (static_cast<double>(c.waited) * c.dt >= c.rule.time_limit_seconds - 1e-9) {
      info.dropped = c.skills[target]->name();
      c.pending = c.skills.size();
    }
  }
  return info;
}

const PoseMatcher& Controller::Impl::matcher(std::size_t target) {
  matchers.resize(skills.size());
  if (matchers[target]) return *matchers[target];
  if (!character_of(*envs[target])) throw Error("skill '" + skills[target]->name() + "': pose matching needs a character environment");
  const std::vector<std::shared_ptr<const Clip>> held = skill_clips(*skills[target]);
  if (held.empty()) throw Error("skill '" + skills[target]->name() + "': pose matching needs the clips its starts come from (init: mocap), or a reference");
  std::vector<const Clip*> clips;
  for (const auto& c : held) clips.push_back(c.get());
  matchers[target] = std::make_unique<PoseMatcher>(clips);
  return *matchers[target];
}

double Controller::Impl::measure(std::size_t target, SwitchRule::By by) {
  if (by == SwitchRule::By::Matching) return matcher(target).readiness(character_of(env())->world().pose());
  const Skill& t = *skills[target];
  // The active skill's own environment observes the character already (placing it would restart
  // its episode); another skill's is put in the character's state.
  const bool own = target == active;
  const SkillDiscriminator* d = t.impl().discriminators.empty() ? nullptr : &t.impl().discriminators.front();
  // A state-transition discriminator also reads the step before: placed first, so that the
  // target's environment ends in the current state with two placements, not three.
  const bool pair = by == SwitchRule::By::Score && d && d->transition == "ss";
  Eigen::VectorXd before;
  if (pair) before = own ? (frames.size() > 1 ? frames[frames.size() - 2] : frames.back()) : place(target, std::min<std::size_t>(1, states.size() - 1));
  const Eigen::VectorXd now = own ? frames.back() : place(target, 0);
  const Eigen::VectorXd fresh = now.replicate(t.history(), 1);  // a fresh history: the current frame repeated
  if (by == SwitchRule::By::Value) return t.value(Eigen::MatrixXd(fresh.transpose()))[0];
  if (!d) throw Error("skill '" + t.name() + "' has no discriminator to score with (its networks.mimic holds none)");
  if (d->contexts > 0 || d->context >= 0) throw Error("skill '" + t.name() + "': its discriminator scores under a behaviour context");
  const Eigen::MatrixXd next = now.transpose();
  Eigen::MatrixXd acted = Eigen::MatrixXd::Zero(1, t.action_size());
  if (d->transition == "sa") acted = t.act(Eigen::MatrixXd(fresh.transpose()));
  return d->switch_scores(pair ? Eigen::MatrixXd(before.transpose()) : next, next, acted, -1)[0];
}

void Controller::push(const Eigen::Vector3d& force, double seconds) {
  Impl& c = *impl_;
  if (!force.allFinite() || !(seconds >= 0)) throw Error("push: the force must be finite and the seconds >= 0");
  if (!character_of(c.env())) throw Error("push: skill '" + c.skill().name() + "' drives no character");
  c.push_force = force;
  c.push_left = seconds;
}

bool Controller::throw_cube() {
  Impl& c = *impl_;
  CharacterEnv* character = character_of(c.env());
  ProjectileLauncher* launcher = character ? character->projectiles() : nullptr;
  if (!launcher) return false;
  launcher->launch(character->world(), launcher->sample_aim(character->world()), launcher->sample_direction());
  return true;
}

void Controller::switch_to(const std::string& name) {
  Impl& c = *impl_;
  const std::size_t target = c.index_of(name);
  if (target != c.active) c.hand_over(target);
}

void Controller::request(const std::string& name) {
  Impl& c = *impl_;
  const std::size_t target = c.index_of(name);
  c.pending = target == c.active ? c.skills.size() : target;
  c.waited = 0;
}

const std::string& Controller::requested() const {
  static const std::string none;
  return impl_->pending < impl_->skills.size() ? impl_->skills[impl_->pending]->name() : none;
}

void Controller::set_switch_rule(const SwitchRule& rule) {
  if (rule.delay_steps < 0 || !(rule.time_limit_seconds >= 0) || !std::isfinite(rule.threshold))
    throw Error("switch rule: the delay must be >= 0 steps, the time limit >= 0 s and the threshold finite");
  impl_->rule = rule;
}
const SwitchRule& Controller::switch_rule() const { return impl_->rule; }

double Controller::score(const std::string& skill) { return impl_->measure(impl_->index_of(skill), SwitchRule::By::Score); }
double Controller::value(const std::string& skill) { return impl_->measure(impl_->index_of(skill), SwitchRule::By::Value); }
double Controller::matching(const std::string& skill) { return impl_->measure(impl_->index_of(skill), SwitchRule::By::Matching); }

const std::string& Controller::skill() const { return impl_->skill().name(); }
const std::vector<std::shared_ptr<const Skill>>& Controller::skills() const { return impl_->skills; }
double Controller::control_dt() const { return impl_->dt; }
double Controller::time() const { return static_cast<double>(impl_->steps) * impl_->dt; }
long long Controller::steps() const { return impl_->steps; }
void Controller::set_heading(double yaw) {
  if (!std::isfinite(yaw)) throw Error("set_heading: the yaw must be a finite number of radians");
  impl_->heading = std::remainder(yaw, 2 * kPi);
}
double Controller::heading() const { return impl_->heading; }
bool Controller::steerable(const std::string& skill) const { return impl_->goal_offsets[impl_->index_of(skill)] >= 0; }
double Controller::facing() const {
  const CharacterEnv* character = character_of(*impl_->envs[impl_->active]);
  return character ? heading_angle(character->world().pose().rot[0]) : 0.0;
}

double Controller::ground_height(double x, double y) const {
  const CharacterEnv* character = character_of(*impl_->envs[impl_->active]);
  return character ? character->terrain().height(x, y) : 0.0;
}

double Controller::course_half_width() const {
  const CharacterEnv* character = character_of(*impl_->envs[impl_->active]);
  return character ? 0.5 * character->terrain().spec().width : std::nan("");
}

Eigen::Vector3d Controller::root_position() const {
  Env& env = *impl_->envs[impl_->active];
  if (const CharacterEnv* c = character_of(env)) return c->world().root_position();
  // Another MuJoCo environment (the planar walker): its first body's position, as of the last step.
  const mjModel* m = env.physics_model();
  const mjData* d = env.physics_data();
  if (!m || !d || m->nbody < 2) return Eigen::Vector3d::Zero();
  return Eigen::Vector3d(d->xpos[3], d->xpos[4], d->xpos[5]);
}

const CharacterEnv* ControllerInternals::active_character(const Controller& c) { return character_of(*c.impl_->envs[c.impl_->active]); }
const Env& ControllerInternals::active_env(const Controller& c) { return *c.impl_->envs[c.impl_->active]; }

double Controller::highest_joint_height() const {
  const CharacterEnv* character = character_of(*impl_->envs[impl_->active]);
  if (!character) return 0.0;
  const Vec3 root = character->world().root_position();
  double top = -std::numeric_limits<double>::infinity();
  for (const Vec3& p : character->world().link_frames().joint_pos) top = std::max(top, p.z());
  return top - character->terrain().height(root.x(), root.y());
}

int Controller::lying_side() const {
  const CharacterEnv* character = character_of(*impl_->envs[impl_->active]);
  return character ? mimic::lying_side(character->world().pose()) : 0;
}

const Eigen::VectorXd& Controller::last_input() const { return impl_->input; }
const Eigen::VectorXd& Controller::last_action() const { return impl_->action; }
const mjModel_* Controller::physics_model() const { return impl_->envs[impl_->active]->physics_model(); }
mjData_* Controller::physics_data() const { return impl_->envs[impl_->active]->physics_data(); }

}  // namespace mimic
