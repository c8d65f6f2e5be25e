// The `mimic` command: motion tools now; training, evaluation and rendering as they arrive.
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>

#include <filesystem>
#include <string>
#include <new>

#include "app/commands.hpp"
#include "app/stop_requests.hpp"
#include "control/navigation.hpp"
#include "core/blas_kernel.hpp"
#include "core/error.hpp"
#include "learn/trainer/ranks.hpp"

namespace {

int run(int argc, char** argv) {
  CLI::App app{"mimic: physics-based character controllers learnt from human motion"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "mimic 0.1.0");
  mimic::app::add_motion_commands(app);
  mimic::app::add_render_commands(app);
  mimic::app::add_character_scale_command(app);
  mimic::app::add_demo_command(app);
  mimic::app::add_train_commands(app);
  mimic::app::add_imitate_command(app);
  mimic::app::add_imitation_commands(app);
  mimic::app::add_distill_command(app);
  mimic::app::add_eval_command(app);
  mimic::app::add_play_command(app);
  mimic::app::add_report_commands(app);
  mimic::app::add_video_commands(app);
  mimic::app::add_reconstruct_command(app);
  mimic::app::add_complete_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const mimic::Error& e) {
    spdlog::error("{}", e.what());
    return 1;
  } catch (const std::filesystem::filesystem_error& e) {
    // An output that cannot be made (a directory under a file, no permission, a full disk).
    spdlog::error("{}: {}", e.path1().string(), e.code().message());
    return 1;
  } catch (const std::bad_alloc&) {
    spdlog::error("out of memory");
    return 1;
  } catch (const std::exception& e) {
    spdlog::error("unexpected failure: {}", e.what());
    return 2;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  mimic::pin_blas_kernel(argv);  // the same numbers on every machine (may start the program again)
  mimic::register_control_envs();  // the environments above the environment layer (the navigation task)
  try {
    mimic::ranks::init(argc, argv);  // under mpirun: one rank of a run (learn/trainer/ranks.hpp)
  } catch (const mimic::Error& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
  // Only training is one job over several ranks; anything else would run N times over the same files.
  const std::string command = argc > 1 ? argv[1] : "";
  const std::string subcommand = argc > 2 ? argv[2] : "";
  if (mimic::ranks::many() && command != "train" && command != "imitate" && !(command == "bench" && subcommand == "train")) {
    if (mimic::ranks::rank() == 0)
      spdlog::error("`mimic {}` runs in one process; of mimic's commands only `mimic train`, `mimic imitate` and `mimic bench train` run "
                    "over several ranks (mpirun -np N)",
                    command);
    mimic::ranks::finalize();
    return 1;
  }
  // Rank 0 reports the run; the others speak only of their own warnings and errors.
  if (mimic::ranks::rank() > 0) spdlog::set_level(spdlog::level::warn);
  const int code = run(argc, argv);
  // A rank that failed ends them all: the others would wait for it in their next sum.
  if (code != 0) mimic::ranks::abort_all(code);
  mimic::ranks::finalize();
  // A run stopped early by Ctrl-C or SIGTERM saved and ended cleanly, but did not finish: 128 + the
  // signal (app/stop_requests.hpp), after the ranks have ended together.
  if (mimic::app::stop_signal() != 0) return 128 + mimic::app::stop_signal();
  return code;
}
