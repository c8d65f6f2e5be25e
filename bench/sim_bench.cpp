// Control steps per second for the DeepMimic humanoid on MuJoCo, one core, random PD targets
// (the figure DESIGN.md section 5 compares training throughput against), on flat ground and on a
// staircase (the stairs fine-tune's course: what its box geoms cost a step).
//   build/bench/mimic_bench_sim        (needs ../shared/data or $MIMIC_DATA)
#include <benchmark/benchmark.h>

#include <random>

#include "core/file_io.hpp"
#include "sim/terrain.hpp"
#include "sim/world.hpp"

using namespace mimic;

namespace {

// Random PD targets at `physics_hz` (state.range(0)) on `terrain`, the character started at
// `x` on it and again there whenever it falls.
void humanoid_steps(benchmark::State& state, const TerrainSpec& spec, double x) {
  const auto dir = shared_data_dir() / "deepmimic/characters";
  if (shared_data_dir().empty() || !std::filesystem::exists(dir / "humanoid3d.txt")) {
    state.SkipWithError("shared data not found (../shared/data or $MIMIC_DATA)");
    return;
  }
  const CharacterModel ch = CharacterModel::from_deepmimic(dir / "humanoid3d.txt", dir / "humanoid3d_ctrl.txt");
  const Terrain terrain(spec);
  MjcfOptions opts;
  terrain.add_to(opts);
  World w(ch, SimConfig{static_cast<double>(state.range(0)), 30.0}, opts);
  terrain.install(w.model());
  const Pose start = rest_pose(ch.skeleton, Vec3(x, 0, terrain.height(x, 0) + 0.89));
  w.set_state(start);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(-0.5, 0.5);
  Pose targets = start;
  long resets = 0;
  for (auto _ : state) {
    for (std::size_t j = 1; j < targets.rot.size(); ++j)
      targets.rot[j] = rotvec_to_quat(Vec3(angle(rng), angle(rng), angle(rng)));
    w.set_pd_targets(targets);
    w.step();
    if (w.pose().root_pos.z() - terrain.height(w.pose().root_pos.x(), w.pose().root_pos.y()) < 0.4) {  // fallen: start again
      w.set_state(start);
      ++resets;
    }
  }
  state.counters["steps/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["resets"] = static_cast<double>(resets);
}

void BM_HumanoidControlStep(benchmark::State& state) { humanoid_steps(state, TerrainSpec{}, 0.0); }

void BM_HumanoidControlStepOnStairs(benchmark::State& state) {
  TerrainSpec stairs;
  stairs.kind = TerrainKind::Stairs;
  stairs.step_height = 0.1;
  humanoid_steps(state, stairs, 3.0);  // on the fourth step up
}
BENCHMARK(BM_HumanoidControlStep)->Arg(600)->Arg(1200)->MinTime(3.0)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_HumanoidControlStepOnStairs)->Arg(600)->MinTime(3.0)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
