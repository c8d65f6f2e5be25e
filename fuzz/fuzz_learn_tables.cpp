// Fuzz target: the CSV tables of a run, demonstrations (with their layout line) and metrics.csv.
// The first byte chooses the reader; any input must parse or raise mimic::Error, never crash, and
// parsed demonstrations must be consistent (rows of the header's widths, finite values).
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "core/error.hpp"
#include "fuzz_common.hpp"
#include "fuzz_seeds.hpp"
#include "learn/imitation/demonstrations.hpp"
#include "learn/trainer/run_log.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const std::string text(mimic::fuzz::as_text(data + 1, size - 1));
  try {
    if (data[0] % 2 == 0) {
      const mimic::Demonstrations d = mimic::parse_demonstrations(text, "fuzz.csv");
      if (d.obs.rows() != d.next_obs.rows() || d.obs.rows() != d.action.rows() || d.obs.cols() != d.next_obs.cols() ||
          static_cast<std::size_t>(d.obs.rows()) != d.episode.size())
        mimic::fuzz::fail_with_input(data, size, "demonstrations of inconsistent sizes");
    } else {
      const mimic::MetricsTable t = mimic::parse_metrics_csv(text, "metrics.csv");
      for (const auto& row : t.rows)
        if (row.size() != t.columns.size()) mimic::fuzz::fail_with_input(data, size, "a ragged metrics table");
    }
  } catch (const mimic::Error&) {
  }
  return 0;
}

std::vector<std::string> MimicFuzzSeeds() {
  return {
      std::string("D") + "# layout: pos 0 2, vel 2 1\nepisode,obs_0,obs_1,obs_2,action_0,next_obs_0,next_obs_1,next_obs_2\n"
                         "0,0.1,0.2,0.3,1,0.2,0.3,0.4\n0,0.2,0.3,0.4,-1,0.3,0.4,0.5\n1,1,2,3,0.5,2,3,4\n",
      std::string("D") + "episode,obs_0,next_obs_0\n0,1,2\n",
      std::string("M") + "iteration,samples,return,kl\n1,1024,2.5,0.01\n2,2048,,0.02\n3,3072,4.25,nan\n",
  };
}
