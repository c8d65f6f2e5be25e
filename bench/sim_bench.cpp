// Control steps per second for the DeepMimic humanoid on MuJoCo, one core, random PD targets
// (the figure DESIGN.md section 5 compares training throughput against).
//   build/bench/mimic_bench_sim        (needs ../shared/data or $MIMIC_DATA)
#include <benchmark/benchmark.h>

#include <random>

#include "core/file_io.hpp"
#include "sim/world.hpp"

using namespace mimic;

namespace {

void BM_HumanoidControlStep(benchmark::State& state) {
  const auto dir = shared_data_dir() / "deepmimic/characters";
  if (shared_data_dir().empty() || !std::filesystem::exists(dir / "humanoid3d.txt")) {
    state.SkipWithError("shared data not found (../shared/data or $MIMIC_DATA)");
    return;
  }
  const CharacterModel ch = CharacterModel::from_deepmimic(dir / "humanoid3d.txt", dir / "humanoid3d_ctrl.txt");
  World w(ch, SimConfig{static_cast<double>(state.range(0)), 30.0});
  const Pose start = rest_pose(ch.skeleton, Vec3(0, 0, 0.89));
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
    if (w.pose().root_pos.z() < 0.4) {  // fallen: start again, as an episode would
      w.set_state(start);
      ++resets;
    }
  }
  state.counters["steps/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["resets"] = static_cast<double>(resets);
}
BENCHMARK(BM_HumanoidControlStep)->Arg(600)->Arg(1200)->MinTime(3.0)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
