#include "control/play_session.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/error.hpp"

namespace mimic {

PlaySession::PlaySession(std::vector<std::shared_ptr<const Skill>> skills, PlayOptions options)
    : controller_(skills, options.seed),
      options_(std::move(options)),
      down_(1.0, options_.down_height, options_.down_frames),
      rng_(options_.seed) {
  controller_.set_switch_rule(options_.rule);
  for (const std::string& r : options_.recovery)
    if (std::none_of(skills.begin(), skills.end(), [&](const auto& s) { return s->name() == r; }))
      throw Error("play: no skill '" + r + "' to recover with (the skills are those given to play)");
  reset();
  events_.clear();
}

void PlaySession::reset() {
  controller_.switch_to(controller_.skills().front()->name());
  controller_.reset();
  wanted_ = controller_.skill();
  recovering_ = false;
  down_.restart(controller_.root_position().z());
  log("reset", wanted_);
}

bool PlaySession::request(std::size_t index) {
  const auto& skills = controller_.skills();
  if (index >= skills.size()) return false;
  wanted_ = skills[index]->name();
  log("request", wanted_);
  // While a get-up has the character, the request is what it hands back to.
  controller_.request(wanted_);
  return true;
}

void PlaySession::push(const Eigen::Vector3d& direction) {
  Eigen::Vector3d d(direction.x(), direction.y(), 0.0);
  if (!(d.norm() > 0)) throw Error("push: the direction must have a horizontal part");
  controller_.push(options_.push_force * d.normalized(), options_.push_seconds);
  log("push", controller_.skill());
}

void PlaySession::push() {
  const double a = std::uniform_real_distribution<double>(0.0, 2 * std::numbers::pi)(rng_);
  push(Eigen::Vector3d(std::cos(a), std::sin(a), 0.0));
}

bool PlaySession::steer(double degrees) {
  const auto& skills = controller_.skills();
  if (std::none_of(skills.begin(), skills.end(), [this](const auto& s) { return controller_.steerable(s->name()); })) return false;
  const double from = std::isnan(controller_.heading()) ? controller_.facing() : controller_.heading();
  controller_.set_heading(from + degrees * std::numbers::pi / 180.0);
  log("steer", controller_.skill());
  return true;
}

bool PlaySession::throw_cube() {
  if (!controller_.throw_cube()) return false;
  log("cube", controller_.skill());
  return true;
}

std::vector<double> PlaySession::scores() {
  std::vector<double> out;
  for (const auto& s : controller_.skills())
    out.push_back(s->discriminators().empty() ? std::nan("") : controller_.score(s->name()));
  return out;
}

void PlaySession::start_recovery() {
  // The get-up that fits the character's state: the one whose discriminators score it highest
  // (seed 004 §6's recovery policy checks its own score); without discriminators, the first.
  std::string best = options_.recovery.front();
  double best_score = -std::numeric_limits<double>::infinity();
  for (const std::string& r : options_.recovery) {
    const auto& skills = controller_.skills();
    const auto it = std::find_if(skills.begin(), skills.end(), [&](const auto& s) { return s->name() == r; });
    if ((*it)->discriminators().empty()) continue;
    const double score = controller_.score(r);
    if (score > best_score) best_score = score, best = r;
  }
  controller_.switch_to(best);
  recovering_ = true;
  log("recovering", best);
  if (wanted_ != best) controller_.request(wanted_);
}

void PlaySession::step() {
  const StepInfo info = controller_.step();
  time_ += controller_.control_dt();
  if (!info.switched_to.empty()) {
    log("switch", info.switched_to);
    if (recovering_ && info.switched_to == wanted_) {
      recovering_ = false;
      log("recovered", wanted_);
    }
  }
  if (!info.dropped.empty()) {
    if (recovering_ && info.dropped == wanted_)
      controller_.request(wanted_);  // the get-up is not done yet: the skill asked for waits on
    else
      log("dropped", info.dropped);
  }
  if (down_.update(controller_.root_position().z(), info.ground_contact)) {
    log("down", controller_.skill());
    if (!options_.recovery.empty()) start_recovery();
  }
}

}  // namespace mimic
