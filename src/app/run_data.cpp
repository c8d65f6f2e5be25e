#include "app/run_data.hpp"

namespace mimic::app {

namespace fs = std::filesystem;

std::vector<std::string> copy_run_data(const fs::path& run, const fs::path& model) {
  std::vector<std::string> copied;
  for (const char* own : {"clips", "start_clips", "character", "demos.csv"}) {
    if (!fs::exists(run / own)) continue;
    fs::remove_all(model / own);
    fs::copy(run / own, model / own, fs::copy_options::recursive);
    copied.emplace_back(own);
  }
  return copied;
}

}  // namespace mimic::app
