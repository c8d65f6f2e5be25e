// Loads a trained skill, steps its character for 10 s and prints how far it walked.
//   walk [MODEL_DIR]   (default models/humanoid_walk_iccgan, run from mimic's source tree)
#include <mimic/runtime.hpp>

#include <cstdio>
#include <exception>

int main(int argc, char** argv) {
  try {
    const std::filesystem::path model = argc > 1 ? argv[1] : "models/humanoid_walk_iccgan";
    const std::shared_ptr<const mimic::Skill> skill = mimic::Skill::load(model);
    mimic::Controller controller({skill});
    const Eigen::Vector3d start = controller.root_position();
    int falls = 0;
    while (controller.time() < 10.0) {
      const mimic::StepInfo step = controller.step();
      if (step.fell) ++falls;
      if (step.episode_over) break;
    }
    const Eigen::Vector3d end = controller.root_position();
    std::printf("%s walked %.2f m in %.1f s (%lld steps of %.4f s), falls: %d\n", skill->name().c_str(), (end - start).head<2>().norm(),
                controller.time(), controller.steps(), controller.control_dt(), falls);
    return falls == 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "walk: %s\n", e.what());
    return 2;
  }
}
