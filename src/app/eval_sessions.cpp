// `mimic eval`'s measurements in runtime sessions of several skills (control/): seed 004 §6.5's
// transition test (--transitions) and robustness with recovery (--recover); and a steered skill's
// response to commanded turns (--steering) and the crossing of a course (--crossing).
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "app/commands.hpp"
#include "app/evaluate.hpp"
#include "app/run_skill.hpp"
#include "control/performing.hpp"
#include "control/skill_impl.hpp"
#include "control/transitions.hpp"
#include "core/error.hpp"
#include "core/statistics.hpp"
#include "env/imitation_env.hpp"
#include "learn/imitation/crossing_eval.hpp"
#include "learn/imitation/steering_eval.hpp"

namespace mimic::app {

// Seed 004 section 6.5's transition test between this skill and the others (control/transitions.hpp).
std::string transitions(const EvalArgs& args, const std::shared_ptr<const Skill>& skill) {
  std::vector<std::shared_ptr<const Skill>> skills{skill};
  for (const auto& other : args.transitions) skills.push_back(run_skill(other, args.settings, /*discriminators=*/true));
  TransitionOptions o;
  o.trials = args.transition_trials;
  o.seed = args.seed;
  if (!args.transition_taus.empty()) o.thresholds = args.transition_taus;
  const auto has = [&](const char* rule) { return std::find(args.transition_rules.begin(), args.transition_rules.end(), rule) != args.transition_rules.end(); };
  if (!has("score") && !has("value") && !has("matching") && !has("immediately")) throw Error("--transition-rules: name at least one rule");
  o.score_rule = has("score");
  o.value_baseline = has("value");
  o.matching_baseline = has("matching");
  o.immediate_baseline = has("immediately");
  spdlog::info("  transitions     {} skills, every ordered pair; {} trials per rule; request {:.0f}-{:.0f} s into the first skill (40-80 % of a "
               "shorter episode); success: "
               "the second takes over within {:.0f} s and stays up {:.0f} s with its score above {:.1f} over the last second",
               skills.size(), o.trials, o.earliest_request, o.latest_request, o.time_limit_seconds, o.hold_seconds, o.performing_score);
  std::string json = ", \"transitions\": {\"hold_seconds\": " + json_number(o.hold_seconds) + ", \"time_limit_seconds\": " +
                     json_number(o.time_limit_seconds) + ", \"performing_score\": " + json_number(o.performing_score) + ", \"cells\": [";
  bool first = true;
  (void)measure_transitions(skills, o, [&](const TransitionCell& c) {
    spdlog::info("    {} -> {}  {:<11} {}  success {:3.0f} % ({} of {}), switched {}, fell {}, wait {:.2f} s", c.from, c.to, c.rule,
                 c.rule != "immediately" ? fmt::format("tau {:4.1f}", c.threshold) : std::string(8, ' '), 100.0 * c.success_rate(), c.succeeded,
                 c.trials, c.switched, c.fell, c.mean_wait);
    json += fmt::format("{}{{\"from\": {}, \"to\": {}, \"rule\": \"{}\", \"threshold\": {}, {}\"trials\": {}, \"switched\": {}, "
                        "\"succeeded\": {}, \"fell\": {}, \"success_rate\": {}, \"mean_wait\": {}}}",
                        first ? "" : ", ", json_string(c.from), json_string(c.to), c.rule, json_number(c.threshold),
                        c.rule == "value" ? "\"value_threshold\": " + json_number(c.value_threshold) + ", " : std::string(), c.trials, c.switched,
                        c.succeeded, c.fell, json_number(c.success_rate()), json_number(c.mean_wait));
    first = false;
  });
  return json + "]}";
}

// Seed 004 §6's robustness with recovery: at each cube mass, the skill performs under the
// projectile test in a play session, without and with the --recover get-ups; the fraction of the
// time it spends performing (control/performing.hpp).
std::string recovery(const EvalArgs& args) {
  PerformingOptions o;
  o.seconds = args.robustness_seconds;
  o.trials = args.robustness_trials;
  o.seed = args.seed;
  o.hand_back_threshold = args.recover_tau;
  spdlog::info("  recovery        the fraction of {:.0f} s spent performing under the cubes, without and with the get-ups ({}); {} trials per "
               "mass; the skill takes the character back when the get-up is done, at score >= {:.2f}",
               o.seconds, args.recover.size(), o.trials, o.hand_back_threshold);
  std::string json = ", \"recovery\": {\"seconds\": " + json_number(o.seconds) + ", \"trials\": " + std::to_string(o.trials) +
                     ", \"tau\": " + json_number(o.hand_back_threshold) + ", \"get_ups\": [";
  for (std::size_t i = 0; i < args.recover.size(); ++i) json += (i ? ", " : "") + json_string(args.recover[i].string());
  json += "], \"masses\": [";
  for (std::size_t i = 0; i < args.masses.size(); ++i) {
    const double mass = args.masses[i];
    const std::vector<std::string> settings = projectile_settings(args, mass);
    std::vector<std::shared_ptr<const Skill>> skills{run_skill(args.run, settings, /*discriminators=*/true)};
    const PerformingReport without = measure_performing(skills, o);
    for (const auto& get_up : args.recover) skills.push_back(run_skill(get_up, settings, /*discriminators=*/true));
    const PerformingReport with = measure_performing(skills, o);
    spdlog::info("    {}  performing {:.2f} +- {:.2f} without recovery ({:.1f} falls a trial), {:.2f} +- {:.2f} with ({:.1f} falls, {:.1f} recovered)",
                 mass > 0 ? fmt::format("{:6.2f} kg", mass) : std::string("no cubes "), without.mean(), without.std(), without.mean_downs(),
                 with.mean(), with.std(), with.mean_downs(), with.mean_recoveries());
    json += fmt::format("{}{{\"mass\": {}, \"without\": {{\"performing_mean\": {}, \"performing_std\": {}, \"downs_mean\": {}}}, "
                        "\"with\": {{\"performing_mean\": {}, \"performing_std\": {}, \"downs_mean\": {}, \"recovered_mean\": {}}}}}",
                        i ? ", " : "", json_number(mass), json_number(without.mean()), json_number(without.std()), json_number(without.mean_downs()),
                        json_number(with.mean()), json_number(with.std()), json_number(with.mean_downs()), json_number(with.mean_recoveries()));
  }
  return json + "]}";
}

// A skill trained with a heading goal, commanded to turn (learn/imitation/steering_eval.hpp); the
// environment's own redraws of the target are turned off so that the command is the only one.
std::string steering(const EvalArgs& args) {
  SteeringOptions o;
  o.trials = args.steering_trials;
  o.seed = args.seed;
  std::vector<std::string> settings = args.settings;
  settings.push_back("env.goal_period=1000000");
  settings.push_back(fmt::format("env.max_seconds={}", o.settle_seconds + o.hold_seconds + 1.0));
  const std::shared_ptr<const Skill> skill = run_skill(args.run, settings);
  const std::unique_ptr<Env> env = make_skill_env(*skill);
  CharacterEnv* character = character_of(*env);
  if (!character || !has_heading_goal(*character))
    throw Error(args.run.string() + ": --steering: the skill was not trained with a heading goal (env.goal: heading; `mimic imitate --task heading`)");
  spdlog::info("  steering        {} trials a turn: {:.0f} s straight on, then a turn from the heading held {:.0f} s; error: the command against "
               "the root's travel over the last {:.1f} s, read {:.0f} s after it",
               o.trials, o.settle_seconds, o.hold_seconds, o.travel_seconds, o.respond_seconds);
  std::string json = ", \"steering\": {\"trials\": " + std::to_string(o.trials) + ", \"respond_seconds\": " + json_number(o.respond_seconds) +
                     ", \"tolerance_degrees\": " + json_number(o.tolerance_degrees) + ", \"turns\": [";
  for (std::size_t i = 0; i < args.steering.size(); ++i) {
    o.turn_degrees = args.steering[i];
    SteeringReport r;
    try {
      r = measure_steering(*character, [&skill](const Eigen::VectorXd& input) { return skill->act(input); }, skill->history(), o);
    } catch (const Error& e) {
      throw Error(args.run.string() + ": --steering: " + e.what());
    }
    const double median_time = median_of(r.seconds_to_tolerance);
    spdlog::info("    {:5.0f} deg     within {:.0f} deg after {:.0f} s: {:3.0f} % ({} fell); error {:.1f} deg median, {:.1f} mean; first within "
                 "{:.0f} deg: {} (median); {:.2f} m/s along the command",
                 o.turn_degrees, o.tolerance_degrees, r.respond_seconds, 100.0 * r.success_rate(), r.falls, median_of(r.error_degrees),
                 mean_of(r.error_degrees), o.tolerance_degrees, std::isfinite(median_time) ? fmt::format("after {:.2f} s", median_time) : "never",
                 mean_of(r.speed_along));
    json += fmt::format("{}{{\"turn_degrees\": {}, \"success_rate\": {}, \"falls\": {}, \"error_degrees_median\": {}, "
                        "\"error_degrees_mean\": {}, \"error_degrees\": {}, \"seconds_to_tolerance_median\": {}, \"speed_along_mean\": {}}}",
                        i ? ", " : "", json_number(o.turn_degrees), json_number(r.success_rate()), r.falls, json_number(median_of(r.error_degrees)),
                        json_number(mean_of(r.error_degrees)), json_numbers(r.error_degrees), json_number(median_time),
                        json_number(mean_of(r.speed_along)));
  }
  return json + "]}";
}

// The run's course crossed (learn/imitation/crossing_eval.hpp): its own terrain, or another given
// by --set env.terrain={...}; a skill with a heading goal is commanded along the course.
std::string crossing(const EvalArgs& args) {
  CrossingOptions o;
  o.trials = args.crossing_trials;
  o.seconds = args.crossing_seconds;
  o.seed = args.seed;
  std::vector<std::string> settings = args.settings;
  settings.push_back(fmt::format("env.max_seconds={}", o.seconds + 1.0));
  std::shared_ptr<const Skill> skill = run_skill(args.run, settings);
  const std::unique_ptr<Env> probe = make_skill_env(*skill);
  const CharacterEnv* probed = character_of(*probe);
  if (!probed) throw Error(args.run.string() + ": --crossing needs a character environment");
  if (probed->terrain().spec().kind == TerrainKind::Flat)
    throw Error(args.run.string() + ": --crossing: the run's ground is flat; give a course, e.g. --set \"env.terrain={kind: stairs, step_height: 0.1}\"");
  if (has_heading_goal(*probed)) {  // the command is the only target
    settings.push_back("env.goal_period=1000000");
    skill = run_skill(args.run, settings);
  }
  const std::unique_ptr<Env> env = make_skill_env(*skill);
  CharacterEnv* character = character_of(*env);
  const TerrainSpec& course = character->terrain().spec();
  CrossingReport r;
  try {
    r = measure_crossing(*character, [&skill](const Eigen::VectorXd& input) { return skill->act(input); }, skill->history(), o);
  } catch (const Error& e) {
    throw Error(args.run.string() + ": --crossing: " + e.what());
  }
  spdlog::info("  crossing        {} trials of at most {:.0f} s over the {} course{}; across: the root {:.1f} m past its last feature (x = {:.2f} m) "
               "before it is down", r.trials, r.seconds, to_string(course.kind),
               course.kind == TerrainKind::Stairs ? fmt::format(" (steps {:.2f} m high, {:.2f} m deep)", course.step_height, course.step_depth) : "",
               o.margin, r.finish_x);
  spdlog::info("    crossed {} of {} ({:.0f} %), down {}, stopped short {}; progress {:.2f} of the course (mean){}", r.crossed, r.trials,
               100.0 * r.success_rate(), r.falls, r.trials - r.crossed - r.falls, mean_of(r.progress),
               r.seconds_to_cross.empty() ? std::string() : fmt::format("; {:.1f} s to cross (median)", median_of(r.seconds_to_cross)));
  return fmt::format(", \"crossing\": {{\"terrain\": \"{}\", \"step_height\": {}, \"finish_x\": {}, \"trials\": {}, \"seconds\": {}, "
                     "\"crossed\": {}, \"falls\": {}, \"success_rate\": {}, \"progress_mean\": {}, \"progress\": {}, "
                     "\"seconds_to_cross_median\": {}}}",
                     to_string(course.kind), course.kind == TerrainKind::Stairs ? json_number(course.step_height) : "null", json_number(r.finish_x),
                     r.trials, json_number(r.seconds), r.crossed, r.falls, json_number(r.success_rate()), json_number(mean_of(r.progress)),
                     json_numbers(r.progress), json_number(median_of(r.seconds_to_cross)));
}

}  // namespace mimic::app
