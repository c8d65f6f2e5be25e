// Where the humanoid's simulation step spends its time, under MuJoCo's solver and collision
// options: one core, random PD targets (as bench/sim_bench.cpp), one row per setting with control
// steps/s, the solver's mean iterations, MuJoCo's own timers (collision, making and solving the
// constraints, the rest of the dynamics) and mimic's PD controller, and how far the character's
// root has moved from where the default settings take it after the same targets.
//   build/bench/mimic_sim_profile [control steps, default 3000]   (needs ../shared/data or $MIMIC_DATA)
#include <mujoco/mujoco.h>

#include <chrono>
#include <cstdio>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "core/file_io.hpp"
#include "sim/world.hpp"

using namespace mimic;

namespace {

mjtNum now_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

struct Setting {
  std::string name;
  std::function<void(mjModel*)> apply;
};

struct Row {
  double steps_per_s = 0, solver_iterations = 0, collision = 0, constraint = 0, dynamics = 0, pd = 0, drift = 0;
};

Row run(const CharacterModel& ch, const Setting& setting, int steps, std::vector<Vec3>* roots) {
  World w(ch, SimConfig{600.0, 30.0});
  setting.apply(w.model());
  const Pose start = rest_pose(ch.skeleton, Vec3(0, 0, 0.89));
  w.set_state(start);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(-0.5, 0.5);
  Pose targets = start;
  long solver_iterations = 0;
  // MuJoCo's timers, summed after every control step (a reset after a fall clears them).
  double step_time = 0, collision = 0, constraint = 0;
  auto take_timers = [&] {
    mjTimerStat* t = w.data()->timer;
    step_time += t[mjTIMER_STEP].duration;
    collision += t[mjTIMER_POS_COLLISION].duration;
    constraint += t[mjTIMER_POS_MAKE].duration + t[mjTIMER_POS_PROJECT].duration + t[mjTIMER_CONSTRAINT].duration;
    for (int k = 0; k < mjNTIMER; ++k) t[k].duration = 0, t[k].number = 0;
  };
  Row row;
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < steps; ++i) {
    for (std::size_t j = 1; j < targets.rot.size(); ++j) targets.rot[j] = rotvec_to_quat(Vec3(angle(rng), angle(rng), angle(rng)));
    w.set_pd_targets(targets);
    w.step();
    solver_iterations += w.data()->solver_iter;
    take_timers();
    if (roots) {
      if (static_cast<int>(roots->size()) <= i) roots->push_back(w.pose().root_pos);
      else row.drift = std::max(row.drift, (w.pose().root_pos - (*roots)[static_cast<std::size_t>(i)]).norm());
    }
    if (w.pose().root_pos.z() < 0.4) w.set_state(start);  // fallen: start again, as an episode would
  }
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  row.steps_per_s = steps / total;
  row.solver_iterations = static_cast<double>(solver_iterations) / static_cast<double>(steps);  // at the last substep of each
  row.collision = collision / total;
  row.constraint = constraint / total;
  row.dynamics = step_time / total - row.collision - row.constraint;
  row.pd = 1.0 - step_time / total;  // mimic's side: PD torques, targets, pose reads
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  const int steps = argc > 1 ? std::stoi(argv[1]) : 3000;
  const auto dir = shared_data_dir() / "deepmimic/characters";
  if (shared_data_dir().empty() || !std::filesystem::exists(dir / "humanoid3d.txt")) {
    std::fprintf(stderr, "shared data not found (../shared/data or $MIMIC_DATA)\n");
    return 1;
  }
  mjcb_time = now_seconds;
  const CharacterModel ch = CharacterModel::from_deepmimic(dir / "humanoid3d.txt", dir / "humanoid3d_ctrl.txt");
  const std::vector<Setting> settings = {
      {"default (Newton, 100 iterations, tolerance 1e-8, pyramidal cone)", [](mjModel*) {}},
      {"tolerance 1e-6", [](mjModel* m) { m->opt.tolerance = 1e-6; }},
      {"tolerance 1e-5", [](mjModel* m) { m->opt.tolerance = 1e-5; }},
      {"iterations 5", [](mjModel* m) { m->opt.iterations = 5; }},
      {"iterations 2", [](mjModel* m) { m->opt.iterations = 2; }},
      {"MPR tolerance 1e-4", [](mjModel* m) { m->opt.mpr_tolerance = 1e-4; }},
      {"CG solver", [](mjModel* m) { m->opt.solver = mjSOL_CG; }},
      {"PGS solver", [](mjModel* m) { m->opt.solver = mjSOL_PGS; }},
      {"elliptic cone", [](mjModel* m) { m->opt.cone = mjCONE_ELLIPTIC; }},
      {"sparse Jacobian", [](mjModel* m) { m->opt.jacobian = mjJAC_SPARSE; }},
      {"no warm start", [](mjModel* m) { m->opt.disableflags |= mjDSBL_WARMSTART; }},
  };
  std::printf("humanoid3d, 600 Hz physics / 30 Hz control, %d control steps of random PD targets, one core\n\n", steps);
  std::printf("| setting | control steps/s | vs default | solver iterations | collision | constraints | other dynamics | PD and reads | root vs default (max, m) |\n");
  std::printf("| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
  std::vector<Vec3> roots;
  double base = 0;
  for (const Setting& s : settings) {
    const Row r = run(ch, s, steps, &roots);
    if (base == 0) base = r.steps_per_s;
    std::printf("| %s | %.0f | %.2fx | %.1f | %.0f%% | %.0f%% | %.0f%% | %.0f%% | %.3f |\n", s.name.c_str(), r.steps_per_s, r.steps_per_s / base,
                r.solver_iterations, 100 * r.collision, 100 * r.constraint, 100 * r.dynamics, 100 * r.pd, r.drift);
  }
  return 0;
}
