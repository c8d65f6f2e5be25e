// A play session (mimic play, and the demo's finale): the skills of one character in a window
// (or headless, from a script): keys request skills, push the character, throw cubes; a fallen
// character is got up by the recovery skills. A navigation controller drives its steered skill on
// its course by itself. The session's events go to a JSON file (docs/interactive.md).
#include <mujoco/mujoco.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <sstream>
#include <numbers>
#include <thread>

#include "app/play_run.hpp"
#include "control/controller_internals.hpp"
#include "control/navigation.hpp"
#include "control/play_session.hpp"
#include "control/skill_impl.hpp"
#include "core/error.hpp"
#include "core/file_io.hpp"
#include "env/env_factory.hpp"
#include "motion/clip_io.hpp"
#include "render/offscreen.hpp"
#include "render/video_writer.hpp"
#include "render/window.hpp"

namespace mimic::app {

namespace {

// The keys a script or the window gives, and what each does (the help text and the docs).
const std::vector<std::string> kKeys = {"1", "2", "3", "4", "5", "6", "7", "8", "9", "p", "b", "r", "c", "v", "space", "left", "right", "up", "down", "escape"};

struct ScriptLine {
  double t = 0;
  std::string key;
};

// Lines of "SECONDS KEY" (keys as kKeys; '#' starts a comment), in time order.
std::vector<ScriptLine> read_script(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw Error(path.string() + ": cannot open the script");
  std::vector<ScriptLine> out;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (const auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream words(line);
    std::string time, key, extra;
    if (!(words >> time)) continue;
    const std::string where = path.string() + ":" + std::to_string(n) + ": ";
    if (!(words >> key)) throw Error(where + "expected 'SECONDS KEY', found only '" + time + "'");
    if (words >> extra) throw Error(where + "expected 'SECONDS KEY', found more after the key: '" + extra + "'");
    char* end = nullptr;
    const double t = std::strtod(time.c_str(), &end);
    if (end == time.c_str() || *end != '\0' || !std::isfinite(t) || t < 0) throw Error(where + "'" + time + "' is not a time in seconds >= 0");
    for (auto& ch : key) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    if (std::find(kKeys.begin(), kKeys.end(), key) == kKeys.end()) {
      std::string known;
      for (const auto& k : kKeys) known += (known.empty() ? "" : " ") + k;
      throw Error(where + "unknown key '" + key + "' (keys: " + known + ")");
    }
    if (!out.empty() && t < out.back().t) throw Error(where + "the times must not go back (" + time + " after " + fmt::format("{}", out.back().t) + ")");
    out.push_back({t, key});
  }
  return out;
}

// The views C cycles through, all following the character's root.
const std::vector<CameraSpec> kViews = {
    CameraSpec{Vec3::Zero(), 4.0, 90.0, -12.0},    // its left side
    CameraSpec{Vec3::Zero(), 4.5, 180.0, -15.0},   // from behind (it walks along +x)
    CameraSpec{Vec3::Zero(), 4.0, 0.0, -12.0},     // from the front
    CameraSpec{Vec3::Zero(), 7.0, 135.0, -35.0},   // from above
};


// An environment with a view of its own (Env::view_camera: the reacher's from above) is first seen by it; then kViews.
bool has_own_camera(const Controller& c) { return ControllerInternals::active_env(c).view_camera() >= 0; }
std::size_t view_count(const Controller& c) { return kViews.size() + (has_own_camera(c) ? 1 : 0); }

// What the user sees and steers besides the session: the view, pause, recording.
struct View {
  std::size_t view = 0;
  double azimuth_offset = 0, distance_offset = 0;
  bool paused = false, quit = false, record_toggled = false;
  CameraFollow follow;
};

// One key, from the window or the script.
void press(const std::string& key, PlaySession& session, View& view) {
  if (key.size() == 1 && key[0] >= '1' && key[0] <= '9') {
    const auto index = static_cast<std::size_t>(key[0] - '1');
    if (!session.request(index)) spdlog::warn("key {}: there is no skill {} (the session has {})", key, index + 1, session.controller().skills().size());
  } else if (key == "p") {
    session.push();
  } else if (key == "b") {
    if (!session.throw_cube()) spdlog::warn("key b: the active skill's world has no cubes");
  } else if (key == "r") {
    session.reset();
    view.follow.restart();
  } else if (key == "c") {
    view.view = (view.view + 1) % view_count(session.controller());
  } else if (key == "space") {
    view.paused = !view.paused;
  } else if (key == "v") {
    view.record_toggled = true;
  } else if (key == "left" || key == "right") {
    // Steer a skill that takes a heading (30 degrees a press); without one, turn the camera.
    if (!session.steer(key == "left" ? 30.0 : -30.0)) view.azimuth_offset += key == "left" ? -15 : 15;
  } else if (key == "up" || key == "down") {
    view.distance_offset = std::clamp(view.distance_offset + (key == "up" ? -0.5 : 0.5), -3.0, 10.0);
  } else if (key == "escape") {
    view.quit = true;
  }
}

CameraSpec camera(View& view, const Controller& c) {
  const bool own = has_own_camera(c);
  if (own && view.view == 0) {
    CameraSpec its;
    its.model_camera = ControllerInternals::active_env(c).view_camera();
    return its;
  }
  CameraSpec cam = kViews[view.view - (own ? 1 : 0)];
  cam.lookat = view.follow.update(Vec3(c.root_position()));
  cam.lookat.z() = 0.9;
  cam.azimuth += view.azimuth_offset;
  cam.distance += view.distance_offset;
  return cam;
}

// The text over the picture: the active skill, the one asked for, the rule, each skill's score,
// the commanded heading (and the navigation controller commanding it, `driver`, where one does).
Overlay overlay(PlaySession& s, const View& view, const std::string& driver) {
  const Controller& c = s.controller();
  Overlay o;
  o.left = "time\nskill\nasked for\nrule\n";
  // While a get-up has the character, the skill asked for waits for it to be done before its request.
  const std::string asked = !c.requested().empty()                        ? c.requested() + " (waiting)"
                            : s.recovering() && s.wanted() != c.skill() ? s.wanted() + " (after the get-up)"
                                                                        : "-";
  o.right = fmt::format("{:.1f} s{}\n{}{}\n{}\n{} {}\n", s.time(), view.paused ? " (paused)" : "", c.skill(), s.recovering() ? " (getting up)" : "",
                        asked, c.switch_rule().by == SwitchRule::By::Score ? "score >=" : c.switch_rule().by == SwitchRule::By::Value ? "value >=" : "at once",
                        c.switch_rule().by == SwitchRule::By::Immediately ? std::string() : fmt::format("{:.2f}", c.switch_rule().threshold));
  const std::vector<double> scores = s.scores();
  for (std::size_t i = 0; i < scores.size(); ++i) {
    o.left += fmt::format("{} {}\n", i + 1, c.skills()[i]->name());
    o.right += std::isnan(scores[i]) ? "no discriminator\n" : fmt::format("{:+.2f}\n", scores[i]);
  }
  if (!std::isnan(c.heading())) {
    o.left += "heading\n";
    o.right += fmt::format("{:.0f} deg commanded{}, {:.0f} deg facing\n", c.heading() * 180.0 / std::numbers::pi,
                           driver.empty() ? "" : " by " + driver, c.facing() * 180.0 / std::numbers::pi);
  }
  o.left += "keys";
  o.right += "1-9 skill, arrows steer or turn the camera, p push, b cube, r reset, c camera, v record, space pause";
  return o;
}

std::string events_json(const std::vector<PlayEvent>& events) {
  std::string out = "[";
  for (std::size_t i = 0; i < events.size(); ++i)
    out += fmt::format("{}\n  {{\"t\": {}, \"event\": {}, \"skill\": {}}}", i ? "," : "", json_number(std::round(events[i].t * 1e4) / 1e4),
                       json_string(events[i].event), json_string(events[i].skill));
  return out + (events.empty() ? "]\n" : "\n]\n");
}

void write_ppm(const std::filesystem::path& path, const std::vector<std::uint8_t>& rgb, int width, int height) {
  std::string bytes = fmt::format("P6\n{} {}\n255\n", width, height);
  bytes.append(reinterpret_cast<const char*>(rgb.data()), rgb.size());
  write_file_atomic(path, bytes);
}

// Each skill's world gets cubes thrown only on demand.
std::vector<std::string> cube_settings(const PlayArgs& a) {
  return {fmt::format("env.projectiles={{enabled: true, every: 0, mass: {}, speed: {}}}", a.cube_mass, a.cube_speed)};
}

// Whether a model's environment has a simulated character to throw cubes at (the planar walker's
// and the reacher's have none, nor a key for cubes). A directory without a readable config or an
// env name answers true: Skill::load then says what is wrong.
bool takes_cubes(const std::filesystem::path& dir) {
  try {
    const std::string name = model_env_name(dir);
    return name.empty() || env_has_character(name);
  } catch (const Error&) {
    return true;
  }
}

// The skills; all must share one world to be drawn.
std::vector<std::shared_ptr<const Skill>> load_skills(const PlayArgs& a) {
  const std::vector<std::string> settings = cube_settings(a);
  std::vector<std::shared_ptr<const Skill>> skills;
  for (const auto& list : {&a.models, &a.recover})
    for (const auto& dir : *list) {
      spdlog::info("loading {}", dir.string());
      skills.push_back(Skill::load(dir, "", takes_cubes(dir) ? settings : std::vector<std::string>{}));
    }
  return skills;
}

}  // namespace

std::vector<PlayEvent> run_play(const PlayArgs& a) {
  if (a.models.empty()) throw Error("play: give at least one model");
  if (a.models.size() + a.recover.size() > 9) throw Error("play: at most 9 skills (keys 1-9), --recover ones included");
  if (a.headless && a.output.empty() && a.json.empty() && a.motion.empty())
    throw Error("play --headless: give -o (a video), --json (the events) or --motion (the character's motion)");
  if (!a.motion.empty() && a.motion.extension() != ".mclip")
    throw Error("play --motion " + a.motion.string() + ": the character's motion is written as an .mclip (mimic motion convert makes other formats of it)");
  const std::vector<ScriptLine> script = a.script.empty() ? std::vector<ScriptLine>{} : read_script(a.script);
  double seconds = a.seconds;
  if (a.headless && seconds <= 0) {
    if (script.empty()) throw Error("play --headless: give --seconds, or a --script (it then runs 2 s past its last key)");
    seconds = script.back().t + 2.0;
  }
  // What would fail later, before the models load: no display for the window, two skills named alike.
  if (!a.headless) Window::check_display();
  std::vector<std::string> names_seen;
  for (const auto& list : {&a.models, &a.recover})
    for (const auto& dir : *list) {
      const std::string name = Skill::default_name(dir);
      if (std::find(names_seen.begin(), names_seen.end(), name) != names_seen.end())
        throw Error("play: two skills are named '" + name + "' (a skill is named by its directory, a run's RUN/model by its run; give each model once)");
      names_seen.push_back(name);
    }
  PlayOptions o;
  o.rule.by = a.rule == "value" ? SwitchRule::By::Value : a.rule == "immediately" ? SwitchRule::By::Immediately : SwitchRule::By::Score;
  o.rule.threshold = a.tau;
  o.rule.delay_steps = a.delay;
  o.rule.time_limit_seconds = a.time_limit;
  o.hand_back_threshold = a.recover_tau;
  o.push_force = a.push_force;
  o.seed = a.seed;
  // A navigation controller (seed 000's HLC) drives its steered skill on its own course.
  std::unique_ptr<Navigator> navigator;
  for (const auto& dir : a.models)
    if (is_navigation_model(dir) && (a.models.size() > 1 || !a.recover.empty()))
      throw Error("play: " + dir.string() + " is a navigation controller: it plays alone (its skill on its course), without other models or --recover");
  if (is_navigation_model(a.models.front())) {
    spdlog::info("loading {} (a navigation controller) and its skill", a.models.front().string());
    navigator = std::make_unique<Navigator>(a.models.front(), cube_settings(a));
  }
  std::vector<std::shared_ptr<const Skill>> skills = navigator ? std::vector{navigator->skill()} : load_skills(a);
  for (std::size_t i = a.models.size(); i < skills.size(); ++i) o.recovery.push_back(skills[i]->name());
  PlaySession session(skills, o);
  const mjModel* model = session.controller().physics_model();
  // One picture for every skill's world: the same bodies and geoms (no skill with its own terrain).
  for (const auto& s : skills) {
    const std::unique_ptr<Env> env = make_skill_env(*s);
    const mjModel* m = env->physics_model();
    if (!m || m->nbody != model->nbody || m->ngeom != model->ngeom)
      throw Error("play: skill '" + s->name() + "' (" + s->directory().string() + ") acts in another world than skill '" + skills.front()->name() +
                  "' (its bodies or geoms differ: a terrain?); one window draws one world");
  }
  std::string names;
  for (std::size_t i = 0; i < skills.size(); ++i) names += fmt::format("{}{} {}", i ? ", " : "", i + 1, skills[i]->name());
  spdlog::info("skills: {}{}{}", names, o.recovery.empty() ? "" : " (the last " + std::to_string(o.recovery.size()) + " get a fallen character up)",
               navigator ? ", its heading commanded by " + navigator->controller()->name() + " every " +
                               std::to_string(navigator->config().decision_steps) + " steps"
                         : "");
  const std::string driver = navigator ? navigator->controller()->name() : std::string();
  // The character's motion (--motion): its pose at the start and after every control step taken.
  std::unique_ptr<Clip> motion;
  if (!a.motion.empty()) {
    const CharacterEnv* character = ControllerInternals::active_character(session.controller());
    if (!character) throw Error("play --motion: skill '" + skills.front()->name() + "' drives no character");
    motion = std::make_unique<Clip>();
    motion->name = a.motion.stem().string();
    motion->skeleton = character->world().character().skeleton;
    motion->fps = 1.0 / session.controller().control_dt();
    motion->frames.push_back(character->world().pose());
  }
  // One control step: the controller's decision where one is due, then the skill's step.
  auto advance = [&] {
    if (navigator) navigator->drive(session.controller());
    session.step();
    if (motion) motion->frames.push_back(ControllerInternals::active_character(session.controller())->world().pose());
  };

  const double dt = session.controller().control_dt();
  const long long total_steps = seconds > 0 ? std::llround(seconds / dt) : -1;
  View view;
  std::size_t next_line = 0;
  std::size_t logged = 0;
  auto log_events = [&] {
    for (; logged < session.events().size(); ++logged) {
      const PlayEvent& e = session.events()[logged];
      spdlog::info("{:7.2f} s  {} {}", e.t, e.event, e.skill);
    }
  };
  // The script's keys due at frame `i` (its times count the frames shown, paused ones too, so that
  // a script can pause and go on).
  auto due_keys = [&](long long i) {
    std::vector<std::string> keys;
    for (; next_line < script.size() && script[next_line].t <= static_cast<double>(i) * dt + 1e-9; ++next_line) keys.push_back(script[next_line].key);
    return keys;
  };
  std::vector<std::uint8_t> rgb;

  if (a.headless) {
    OffscreenRenderer renderer(model, a.width, a.height);
    std::unique_ptr<VideoWriter> video = a.output.empty() ? nullptr : std::make_unique<VideoWriter>(a.output, a.width, a.height, 1.0 / dt);
    for (long long i = 0; i < total_steps && !view.quit; ++i) {
      for (const auto& k : due_keys(i)) press(k, session, view);
      if (!view.paused) advance();
      log_events();
      if (video) {
        renderer.render(session.controller().physics_data(), camera(view, session.controller()), rgb, nullptr, overlay(session, view, driver));
        video->write(rgb);
      }
    }
    if (video) video->close();
    if (video) spdlog::info("wrote {} ({} frames)", a.output.string(), video->frames());
  } else {
    Window window(model, a.width, a.height, "mimic play");
    std::unique_ptr<VideoWriter> video;
    std::filesystem::path record_to = a.output.empty() ? std::filesystem::path("play.mp4") : a.output;
    using clock = std::chrono::steady_clock;
    auto next_frame = clock::now();
    const auto frame = std::chrono::duration_cast<clock::duration>(std::chrono::duration<double>(dt));
    for (long long i = 0; (total_steps < 0 || i < total_steps) && !view.quit && !window.closed(); ++i) {
      std::vector<std::string> keys = window.poll();
      for (auto& k : due_keys(i)) keys.push_back(std::move(k));
      for (const auto& k : keys) press(k, session, view);
      if (view.record_toggled) {
        view.record_toggled = false;
        if (video) {
          video->close();
          spdlog::info("wrote {} ({} frames)", record_to.string(), video->frames());
          video.reset();
        } else {
          video = std::make_unique<VideoWriter>(record_to, window.framebuffer_width(), window.framebuffer_height(), 1.0 / dt);
          spdlog::info("recording into {} (v stops)", record_to.string());
        }
      }
      if (!view.paused) advance();
      log_events();
      const bool read = video || !a.screenshot.empty();
      window.draw(session.controller().physics_data(), camera(view, session.controller()), overlay(session, view, driver), read ? &rgb : nullptr);
      if (video) video->write(rgb);
      next_frame += frame;
      std::this_thread::sleep_until(next_frame);
      if (clock::now() > next_frame + 10 * frame) next_frame = clock::now();  // far behind (a slow machine): no catching up
    }
    if (video) {
      video->close();
      spdlog::info("wrote {} ({} frames)", record_to.string(), video->frames());
    }
    if (!a.screenshot.empty()) {
      if (rgb.empty()) throw Error("play: no frame was drawn for --screenshot");
      write_ppm(a.screenshot, rgb, window.framebuffer_width(), window.framebuffer_height());
      spdlog::info("wrote {}", a.screenshot.string());
    }
  }
  log_events();
  if (motion) {
    save_clip(*motion, a.motion);
    spdlog::info("wrote {} ({} frames, {:.2f} s)", a.motion.string(), motion->num_frames(), motion->duration());
  }
  if (!a.json.empty()) {
    write_file_atomic(a.json, events_json(session.events()));
    spdlog::info("wrote {} ({} events)", a.json.string(), session.events().size());
  }
  return session.events();
}

}  // namespace mimic::app
