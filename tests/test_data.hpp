#pragma once
// Locates ../shared/data for tests; tests that need it skip with a clear message when absent.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/file_io.hpp"

namespace mimic::test {

inline std::filesystem::path shared_data() { return shared_data_dir(); }

// Skips the calling test unless `relative` exists under the shared data directory.
#define MIMIC_REQUIRE_SHARED(relative, out_path)                                                     \
  do {                                                                                                \
    const auto mimic_dir_ = ::mimic::test::shared_data();                                             \
    if (mimic_dir_.empty() || !std::filesystem::exists(mimic_dir_ / (relative)))                      \
      GTEST_SKIP() << "shared data '" << (relative)                                                   \
                   << "' not found (looked in $MIMIC_DATA and ../shared/data); skipping";             \
    (out_path) = mimic_dir_ / (relative);                                                             \
  } while (0)

// A fresh temporary directory for one test.
inline std::filesystem::path temp_dir(const std::string& name) {
  auto dir = std::filesystem::path(MIMIC_BINARY_DIR) / "test_tmp" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace mimic::test
