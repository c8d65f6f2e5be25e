#include "control/play_session.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "control/skill_impl.hpp"
#include "core/error.hpp"
#include "motion/clip.hpp"
#include "motion/kinematics.hpp"

namespace mimic {

namespace {
// A get-up has stood the character up when its root and its highest joint are at least this share
// of the heights they have at its clip's end (a kneel, a crouch on the way up, or a body bent over
// at the hips, is lower).
constexpr double kStandingShare = 0.8;
}  // namespace

PlaySession::PlaySession(std::vector<std::shared_ptr<const Skill>> skills, PlayOptions options)
    : controller_(skills, options.seed),
      options_(std::move(options)),
      down_(1.0, options_.down_height, options_.down_frames),
      rng_(options_.seed) {
  controller_.set_switch_rule(options_.rule);
  for (const std::string& r : options_.recovery) {
    const auto it = std::find_if(skills.begin(), skills.end(), [&](const auto& s) { return s->name() == r; });
    if (it == skills.end()) throw Error("play: no skill '" + r + "' to recover with (the skills are those given to play)");
    const auto clips = skill_clips(**it);
    recovery_sides_.push_back(!clips.empty() && begins_lying(*clips.front()) ? lying_side(clips.front()->frames.front()) : 0);
    recovery_seconds_.push_back(clips.empty() ? 0.0 : clips.front()->duration());
    const bool framed = !clips.empty() && !clips.front()->frames.empty();
    recovery_heights_.push_back(framed ? kStandingShare * clips.front()->frames.back().root_pos.z() : 0.0);
    double top = 0.0;
    if (framed)
      for (const Vec3& p : forward_kinematics(clips.front()->skeleton, clips.front()->frames.back()).joint_pos) top = std::max(top, p.z());
    recovery_tops_.push_back(kStandingShare * top);
  }
  reset();
  events_.clear();
}

void PlaySession::reset() {
  controller_.switch_to(controller_.skills().front()->name());
  controller_.reset();
  wanted_ = controller_.skill();
  recovering_ = handing_back_ = false;
  controller_.set_switch_rule(options_.rule);
  down_.restart(controller_.root_position().z());
  log("reset", wanted_);
}

bool PlaySession::request(std::size_t index) {
  const auto& skills = controller_.skills();
  if (index >= skills.size()) return false;
  wanted_ = skills[index]->name();
  log("request", wanted_);
  // While a get-up has the character, the request is what it hands back to when it is done.
  if (!recovering_ || handing_back_) controller_.request(wanted_);
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

std::string PlaySession::get_up_for(int side) {
  const bool any_fits = side != 0 && std::find(recovery_sides_.begin(), recovery_sides_.end(), side) != recovery_sides_.end();
  std::string best;
  double best_score = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < options_.recovery.size(); ++i) {
    if (any_fits && recovery_sides_[i] != side) continue;
    const std::string& r = options_.recovery[i];
    if (best.empty()) best = r;
    const auto& skills = controller_.skills();
    const auto it = std::find_if(skills.begin(), skills.end(), [&](const auto& s) { return s->name() == r; });
    if ((*it)->discriminators().empty()) continue;
    // Seed 004 §6's recovery policy checks its own score: among get-ups of one side, the higher.
    const double score = controller_.score(r);
    if (score > best_score) best_score = score, best = r;
  }
  return best;
}

void PlaySession::start_recovery() { hand_to_get_up(get_up_for(controller_.lying_side())); }

void PlaySession::hand_to_get_up(const std::string& get_up) {
  controller_.switch_to(get_up);
  controller_.request(get_up);  // asking for the active skill cancels a pending request
  controller_.set_switch_rule(options_.rule);
  recovering_ = true;
  handing_back_ = false;
  get_up_since_ = time_;
  other_side_frames_ = 0;
  log("recovering", get_up);
}

bool PlaySession::get_up_done() const {
  const auto at = std::find(options_.recovery.begin(), options_.recovery.end(), controller_.skill());
  if (at == options_.recovery.end()) return true;  // (a get-up asked for by name: the skill asked for has it)
  const auto i = static_cast<std::size_t>(at - options_.recovery.begin());
  const Eigen::Vector3d root = controller_.root_position();
  return !down_.down() && time_ - get_up_since_ >= recovery_seconds_[i] - 1e-9 &&
         root.z() - controller_.ground_height(root.x(), root.y()) >= recovery_heights_[i] &&
         controller_.highest_joint_height() >= recovery_tops_[i];
}

void PlaySession::hand_back() {
  handing_back_ = true;
  if (controller_.skill() == wanted_) {  // the get-up itself was asked for: it keeps the character
    recovering_ = handing_back_ = false;
    log("recovered", wanted_);
    return;
  }
  // The score rule at the hand-back's own threshold (a skill without discriminators: at once).
  const auto& skills = controller_.skills();
  const auto it = std::find_if(skills.begin(), skills.end(), [&](const auto& s) { return s->name() == wanted_; });
  SwitchRule back = options_.rule;
  back.by = (*it)->discriminators().empty() ? SwitchRule::By::Immediately : SwitchRule::By::Score;
  back.threshold = options_.hand_back_threshold;
  back.delay_steps = 0;
  controller_.set_switch_rule(back);
  controller_.request(wanted_);
}

void PlaySession::step() {
  const StepInfo info = controller_.step();
  time_ += controller_.control_dt();
  if (!info.switched_to.empty()) {
    log("switch", info.switched_to);
    if (recovering_ && info.switched_to == wanted_) {
      recovering_ = handing_back_ = false;
      controller_.set_switch_rule(options_.rule);
      log("recovered", wanted_);
    }
  }
  if (!info.dropped.empty()) {
    if (recovering_ && info.dropped == wanted_)
      controller_.request(wanted_);  // the skill asked for waits on until a state allows it
    else
      log("dropped", info.dropped);
  }
  if (down_.update(controller_.root_position().z(), info.ground_contact)) {
    log("down", controller_.skill());
    if (!options_.recovery.empty()) start_recovery();
    return;
  }
  if (!recovering_) return;  // (down again while handing back: start_recovery above began anew)
  // A get-up that finds the character on the other side (it rolled over, or the fall was read
  // wrong) for as long as the down rule waits hands it to the get-up of that side.
  const auto active = std::find(options_.recovery.begin(), options_.recovery.end(), controller_.skill());
  const int side = controller_.lying_side();
  const int own = active == options_.recovery.end() ? 0 : recovery_sides_[static_cast<std::size_t>(active - options_.recovery.begin())];
  other_side_frames_ = own != 0 && side == -own ? other_side_frames_ + 1 : 0;
  if (other_side_frames_ >= options_.down_frames) {
    const std::string get_up = get_up_for(side);
    if (get_up != controller_.skill()) hand_to_get_up(get_up);
    other_side_frames_ = 0;
  }
  // Then, not before, the skill asked for may take the character back.
  if (!handing_back_ && get_up_done()) hand_back();
}

}  // namespace mimic
