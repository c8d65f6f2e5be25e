// Import and forward-kinematics speed on the largest shared clips, in frames per second.
//   build/bench/mimic_bench_motion            (needs ../shared/data or $MIMIC_DATA)
#include <benchmark/benchmark.h>

#include "core/file_io.hpp"
#include "motion/bvh.hpp"
#include "motion/clip_io.hpp"
#include "motion/deepmimic.hpp"
#include "motion/kinematics.hpp"

using namespace mimic;

namespace {

// The largest shared clip: CMU 131_03 (1,102 frames of a 31-joint skeleton at 120 Hz).
const char* kBvh = "cmu-bvh/131_03.bvh";
const char* kDeepMimic = "deepmimic/motions/humanoid3d_getup_faceup.txt";  // largest DeepMimic clip
const char* kCharacter = "deepmimic/characters/humanoid3d.txt";

bool have(benchmark::State& state, const char* rel) {
  const auto dir = shared_data_dir();
  if (dir.empty() || !std::filesystem::exists(dir / rel)) {
    state.SkipWithError("shared data not found (../shared/data or $MIMIC_DATA)");
    return false;
  }
  return true;
}

void BM_ImportBvh(benchmark::State& state) {
  if (!have(state, kBvh)) return;
  const std::string text = read_text_file(shared_data_dir() / kBvh);
  int frames = 0;
  for (auto _ : state) {
    const Clip c = parse_bvh(text, kBvh, AxisConvention{"y", "z", 0.056444});
    frames = c.num_frames();
    benchmark::DoNotOptimize(c.frames.data());
  }
  state.counters["frames/s"] = benchmark::Counter(static_cast<double>(frames) * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ImportBvh)->Unit(benchmark::kMillisecond);

void BM_ImportDeepMimic(benchmark::State& state) {
  if (!have(state, kDeepMimic)) return;
  const Skeleton sk = load_deepmimic_character(shared_data_dir() / kCharacter).skeleton;
  const std::string text = read_text_file(shared_data_dir() / kDeepMimic);
  int frames = 0;
  for (auto _ : state) {
    const Clip c = parse_deepmimic_motion(text, kDeepMimic, sk);
    frames = c.num_frames();
    benchmark::DoNotOptimize(c.frames.data());
  }
  state.counters["frames/s"] = benchmark::Counter(static_cast<double>(frames) * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ImportDeepMimic)->Unit(benchmark::kMillisecond);

void BM_ImportNative(benchmark::State& state) {
  if (!have(state, kBvh)) return;
  const std::string text = write_clip(load_bvh(shared_data_dir() / kBvh, AxisConvention{"y", "z", 0.056444}));
  int frames = 0;
  for (auto _ : state) {
    const Clip c = parse_clip(text, "native.mclip");
    frames = c.num_frames();
    benchmark::DoNotOptimize(c.frames.data());
  }
  state.counters["frames/s"] = benchmark::Counter(static_cast<double>(frames) * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ImportNative)->Unit(benchmark::kMillisecond);

void BM_ForwardKinematics(benchmark::State& state) {
  if (!have(state, kBvh)) return;
  const Clip c = load_bvh(shared_data_dir() / kBvh, AxisConvention{"y", "z", 0.056444});
  LinkFrames fk;
  std::size_t f = 0;
  for (auto _ : state) {
    forward_kinematics(c.skeleton, c.frames[f], fk);
    benchmark::DoNotOptimize(fk.joint_pos.data());
    f = (f + 1) % c.frames.size();
  }
  state.counters["frames/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ForwardKinematics);

}  // namespace

BENCHMARK_MAIN();
