// mimic play MODEL... : the skills of one character in a window (or headless, from a script):
// keys request skills, push the character, throw cubes; a fallen character is got up by the
// --recover skills (the session itself: play_run.cpp; docs/interactive.md).
#include "app/commands.hpp"
#include "app/play_run.hpp"

namespace mimic::app {

void add_play_command(CLI::App& app) {
  auto a = std::make_shared<PlayArgs>();
  CLI::App* play = app.add_subcommand("play", "the skills of one character in a window (or headless from a script): keys request skills, push, throw cubes");
  play->add_option("models", a->models,
                   "model directories (mimic export): keys 1, 2, ... request them; the first starts. A navigation controller (env: "
                   "navigation) plays alone, driving its skill on its course")->required()->check(CLI::ExistingDirectory);
  play->add_option("--recover", a->recover, "get-up models: a character that is down is handed to the one whose clip begins on the side it lies on (face up or down; then by their discriminators' score), and back once it is done")
      ->check(CLI::ExistingDirectory);
  play->add_option("--recover-tau", a->recover_tau,
                   "the score at which the skill asked for takes the character back from a get-up that is done (its clip's duration with the character, and up); -1: at once then")
      ->capture_default_str();
  play->add_option("--rule", a->rule, "when a requested skill takes over: score (its discriminators), value, immediately")
      ->capture_default_str()
      ->check(CLI::IsMember({"score", "value", "immediately"}));
  play->add_option("--tau", a->tau, "the rule's threshold")->capture_default_str();
  play->add_option("--delay", a->delay, "control steps after a take-over before another request may be granted")->capture_default_str()->check(CLI::NonNegativeNumber);
  play->add_option("--time-limit", a->time_limit, "seconds a request waits before it is dropped")->capture_default_str()->check(CLI::NonNegativeNumber);
  play->add_option("--script", a->script, "lines of 'SECONDS KEY' pressed at those times (keys: 1-9 p b r c v space left right up down escape)")
      ->check(CLI::ExistingFile);
  play->add_option("--seconds", a->seconds, "stop after this long (headless default: 2 s past the script's last key)")->check(CLI::PositiveNumber);
  play->add_flag("--headless", a->headless, "no window: run as fast as possible, film into -o");
  play->add_option("-o,--output", a->output, "video (.mp4): headless, the whole session; in the window, what v records (default play.mp4)");
  play->add_option("--json", a->json, "the session's events: [{t, event, skill}] (request, switch, dropped, down, recovering, recovered, push, cube, steer, reset)");
  play->add_option("--screenshot", a->screenshot, "the window's last frame, as a PPM picture");
  play->add_option("--motion", a->motion, "the character's motion over the session, a pose every control step (paused steps left out), as an .mclip: "
                   "for mimic motion convert, another program, or start clips");
  play->add_option("--width", a->width, "pixels")->capture_default_str()->check(CLI::Range(16, 1920));
  play->add_option("--height", a->height, "pixels")->capture_default_str()->check(CLI::Range(16, 1080));
  play->add_option("--push-force", a->push_force, "newtons of a push (p), for 0.2 s")->capture_default_str()->check(CLI::PositiveNumber);
  play->add_option("--cube-mass", a->cube_mass, "kg of a thrown cube (b)")->capture_default_str()->check(CLI::PositiveNumber);
  play->add_option("--cube-speed", a->cube_speed, "m/s of a thrown cube")->capture_default_str()->check(CLI::PositiveNumber);
  play->add_option("--seed", a->seed, "starts and push directions")->capture_default_str();
  play->callback([a] { run_play(*a); });
}

}  // namespace mimic::app
