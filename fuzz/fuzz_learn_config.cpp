// Fuzz target: training configs and --set overrides. The input is a config, optionally followed by
// a line "--set KEY=VALUE" per override; any input must parse or raise mimic::Error, never crash.
#include <cstdint>
#include <sstream>
#include <string_view>

#include "core/error.hpp"
#include "fuzz_common.hpp"
#include "fuzz_seeds.hpp"
#include "learn/trainer/train_config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string input(mimic::fuzz::as_text(data, size));
  std::string text;
  std::vector<std::string> settings;
  std::istringstream lines(input);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("--set ", 0) == 0) settings.push_back(line.substr(6));
    else text += line + "\n";
  }
  try {
    const std::string overridden = mimic::override_config(text, "fuzz.yaml", settings);
    const mimic::TrainConfig cfg = mimic::parse_train_config(overridden, "fuzz.yaml");
    (void)mimic::with_iterations(overridden, "fuzz.yaml", cfg.iterations);
    (void)mimic::config_difference(text, "a.yaml", overridden, "b.yaml");
  } catch (const mimic::Error&) {
  }
  return 0;
}

std::vector<std::string> MimicFuzzSeeds() {
  std::vector<std::string> seeds;
  for (const char* name : {"walker_ci.yaml", "walker_gail.yaml", "humanoid_walk_iccgan_cpu.yaml", "humanoid_walk_tracking.yaml",
                           "humanoid_walk_run_context_iccgan.yaml"}) {
    try {
      seeds.push_back(mimic::read_text_file(std::filesystem::path(MIMIC_SOURCE_DIR) / "configs" / name));
    } catch (const mimic::Error&) {
    }
  }
  seeds.push_back("seed: 2\niterations: 3\nenv: {name: planar_walker}\n--set ppo.clip=0.1\n--set rewards=[{source: env}]\n");
  seeds.push_back("rewards:\n  - {source: gail, expert: x.csv, weight: 0.5}\n--set rewards.0.weight=2\n--set policy.hidden=[8, 8]\n");
  return seeds;
}
