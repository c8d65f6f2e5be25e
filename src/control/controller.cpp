#include <mujoco/mujoco.h>

#include <deque>
#include <random>

#include "control/skill_impl.hpp"
#include "core/error.hpp"
#include "env/character_env.hpp"
#include "env/context_env.hpp"

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

struct Controller::Impl {
  std::vector<std::shared_ptr<const Skill>> skills;
  std::vector<std::unique_ptr<Env>> envs;  // one per skill: its own observation and action mapping
  std::size_t active = 0;
  std::mt19937_64 rng;
  std::deque<Eigen::VectorXd> frames;  // the active skill's last `history` observations, oldest first
  Eigen::VectorXd input, action;
  long long steps = 0;
  double dt = 0.0;  // control step, seconds

  Env& env() { return *envs[active]; }
  const Skill& skill() const { return *skills[active]; }
  void begin(const Eigen::VectorXd& first) {
    frames.assign(static_cast<std::size_t>(skill().history()), first);
    steps = 0;
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
  }
  const CharacterEnv* character = character_of(*impl_->envs.front());
  impl_->dt = character ? 1.0 / character->world().config().control_hz : 0.0;
  reset();
}

Controller::~Controller() = default;

void Controller::reset() { impl_->begin(impl_->env().reset(impl_->rng)); }

StepInfo Controller::step() {
  Impl& c = *impl_;
  c.stack();
  c.action = c.skill().act(c.input);
  const mjData* d = c.env().physics_data();
  const double before = d ? d->time : 0.0;
  const StepResult r = c.env().step(c.action);
  if (d && d->time > before) c.dt = d->time - before;  // environments that are not characters say it here
  ++c.steps;
  c.frames.pop_front();
  c.frames.push_back(r.observation);
  StepInfo info;
  info.episode_over = r.done();
  info.fell = is_failure(r.termination);
  info.ending = ending_name(r.termination);
  return info;
}

void Controller::switch_to(const std::string& name) {
  Impl& c = *impl_;
  std::size_t target = c.skills.size();
  std::string names;
  for (std::size_t i = 0; i < c.skills.size(); ++i) {
    if (c.skills[i]->name() == name) target = i;
    names += (i ? ", " : "") + c.skills[i]->name();
  }
  if (target == c.skills.size()) throw Error("no skill '" + name + "' in this controller (it has " + names + ")");
  if (target == c.active) return;
  CharacterEnv* from = character_of(c.env());
  CharacterEnv* to = character_of(*c.envs[target]);
  if (!from || !to) throw Error("skill '" + name + "': only character environments hand a character over");
  InitState state;
  state.pose = from->world().pose();
  state.velocity = from->world().velocity();
  state.time = from->time();
  const long long steps = c.steps;
  c.active = target;
  c.begin(to->reset(state));
  c.steps = steps;
}

const std::string& Controller::skill() const { return impl_->skill().name(); }
const std::vector<std::shared_ptr<const Skill>>& Controller::skills() const { return impl_->skills; }
double Controller::control_dt() const { return impl_->dt; }
double Controller::time() const { return static_cast<double>(impl_->steps) * impl_->dt; }
long long Controller::steps() const { return impl_->steps; }
Eigen::Vector3d Controller::root_position() const {
  Env& env = *impl_->envs[impl_->active];
  if (const CharacterEnv* c = character_of(env)) return c->world().root_position();
  // Another MuJoCo environment (the planar walker): its first body's position, as of the last step.
  const mjModel* m = env.physics_model();
  const mjData* d = env.physics_data();
  if (!m || !d || m->nbody < 2) return Eigen::Vector3d::Zero();
  return Eigen::Vector3d(d->xpos[3], d->xpos[4], d->xpos[5]);
}
const Eigen::VectorXd& Controller::last_input() const { return impl_->input; }
const Eigen::VectorXd& Controller::last_action() const { return impl_->action; }
const mjModel_* Controller::physics_model() const { return impl_->envs[impl_->active]->physics_model(); }
mjData_* Controller::physics_data() const { return impl_->envs[impl_->active]->physics_data(); }

}  // namespace mimic
