#include "env/navigation_env.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "env/imitation_env.hpp"

namespace mimic {

NavigationEnv::NavigationEnv(std::unique_ptr<CharacterEnv> skill_env, LowLevelPolicy policy, int history, const NavigationConfig& cfg)
    : inner_(std::move(skill_env)), policy_(std::move(policy)), history_(history), cfg_(cfg), view_(cfg) {
  if (!inner_ || !policy_) throw Error("navigation: a skill's environment and policy are needed");
  if (!has_heading_goal(*inner_))
    throw Error("navigation: the low-level skill must take a heading (trained with env.goal: heading, `mimic imitate --task heading`)");
  if (history_ < 1) throw Error("navigation: the skill's history must be at least one frame");
  if (cfg_.decision_steps < 1 || !(cfg_.max_turn > 0 && cfg_.max_turn <= 180) || !(cfg_.view_ahead > 0) || !(cfg_.view_width > 0) ||
      !(cfg_.view_spacing > 0) || !(cfg_.progress_weight >= 0) || !(cfg_.max_seconds > 0))
    throw Error("navigation: decision_steps >= 1, max_turn in (0, 180], positive view sizes and max_seconds, progress_weight >= 0");
  if (view_.ahead * view_.across > 100'000) throw Error("navigation: the view's grid has more than 100,000 cells; give a larger view_spacing");
  for (const ObservationSlice& part : inner_->observation_layout())
    if (part.name == "goal") goal_offset_ = part.offset;
}

NavigationView::NavigationView(const NavigationConfig& c) : cfg(c) {
  if (cfg.view_spacing > 0 && cfg.view_ahead > 0 && cfg.view_width > 0) {  // (NavigationEnv names the error otherwise)
    ahead = static_cast<int>(std::floor(std::min(cfg.view_ahead / cfg.view_spacing, 1e6) + 1e-9)) + 1;
    across = static_cast<int>(std::floor(std::min(cfg.view_width / cfg.view_spacing, 1e6) + 1e-9)) + 1;
  }
}

Eigen::Vector2d NavigationView::point(const Vec3& root, double yaw, int i, int j) const {
  const double along = i * cfg.view_spacing, side = -0.5 * cfg.view_width + j * cfg.view_spacing;
  return {root.x() + std::cos(yaw) * along - std::sin(yaw) * side, root.y() + std::sin(yaw) * along + std::cos(yaw) * side};
}

Eigen::VectorXd NavigationView::observe(const Vec3& root, double yaw, const std::function<double(double, double)>& ground,
                                        double half_width) const {
  Eigen::VectorXd obs(size());
  const int n = size() - 3;
  const double here = n > 0 ? ground(root.x(), root.y()) : 0.0;
  for (int i = 0; n > 0 && i < ahead; ++i)
    for (int j = 0; j < across; ++j) {
      const Eigen::Vector2d p = point(root, yaw, i, j);
      obs[i * across + j] = ground(p.x(), p.y()) - here;
    }
  obs[n] = std::cos(yaw), obs[n + 1] = std::sin(yaw);
  obs[n + 2] = root.y() / half_width;
  return obs;
}

std::vector<ObservationSlice> NavigationEnv::observation_layout() const {
  const int n = view_.size() - 3;
  if (n == 0) return {{"heading", 0, 2}, {"lateral", 2, 1}};
  return {{"height_map", 0, n}, {"heading", n, 2}, {"lateral", n + 2, 1}};
}

double NavigationView::command(double action) const {
  const double a = std::isfinite(action) ? std::clamp(action, -1.0, 1.0) : 0.0;
  return a * cfg.max_turn * kPi / 180.0;
}

double NavigationEnv::command_of(double action) const { return view_.command(action); }

Eigen::Vector2d NavigationEnv::view_point(const Vec3& root, double yaw, int i, int j) const { return view_.point(root, yaw, i, j); }

Eigen::VectorXd NavigationEnv::observe() const {
  const Terrain& terrain = inner_->terrain();
  return view_.observe(inner_->world().root_position(), heading_angle(inner_->world().pose().rot[0]),
                       [&terrain](double x, double y) { return terrain.height(x, y); }, 0.5 * terrain.spec().width);
}

Eigen::VectorXd NavigationEnv::stacked() const {
  const auto frame = frames_.front().size();
  Eigen::VectorXd x(frame * static_cast<Eigen::Index>(frames_.size()));
  for (std::size_t f = 0; f < frames_.size(); ++f) x.segment(static_cast<Eigen::Index>(f) * frame, frame) = frames_[f];
  return x;
}

// The skill's target, and its newest frame made to show it (it was observed under the old one).
void NavigationEnv::command(double yaw) {
  set_goal_heading(*inner_, yaw);
  if (goal_offset_ >= 0) frames_.back().segment(goal_offset_, 2) = goal_observation(*inner_);
}

Eigen::VectorXd NavigationEnv::reset(std::mt19937_64& rng) {
  const Eigen::VectorXd first = inner_->reset(rng);
  frames_.assign(static_cast<std::size_t>(history_), first);
  elapsed_ = 0.0;
  command(0.0);  // along the course until the first decision
  return observe();
}

StepResult NavigationEnv::step(const Eigen::VectorXd& action) {
  if (action.size() != 1) throw Error("navigation: one action value (the heading command) expected, got " + std::to_string(action.size()));
  command(command_of(action[0]));
  const double x0 = inner_->world().root_position().x();
  const double dt = 1.0 / inner_->config().sim.control_hz;
  StepResult out;
  for (int k = 0; k < cfg_.decision_steps && !out.done(); ++k) {
    StepResult r = inner_->step(policy_(stacked()));
    frames_.pop_front();
    frames_.push_back(std::move(r.observation));
    elapsed_ += dt;
    if (r.done()) out.termination = is_failure(r.termination) ? Termination::Fall : Termination::TimeLimit;
    else if (std::abs(inner_->world().root_position().y()) > inner_->terrain().spec().width / 2) out.termination = Termination::Fall;  // off the course
    else if (elapsed_ >= cfg_.max_seconds - 1e-9) out.termination = Termination::TimeLimit;
  }
  out.reward_terms.emplace_back("progress", cfg_.progress_weight * (inner_->world().root_position().x() - x0));
  out.observation = observe();
  return out;
}

}  // namespace mimic
