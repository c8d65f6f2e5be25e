#pragma once
// Helpers shared by the fuzz targets.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "core/file_io.hpp"

namespace mimic::fuzz {

inline std::string_view as_text(const uint8_t* data, size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

// An input the reader accepted but whose result breaks a promise: saved as fuzz-failure.bin in
// the working directory (give it back to the target to repeat the failure), then abort.
[[noreturn]] inline void fail_with_input(const uint8_t* data, size_t size, const std::string& why) {
  std::ofstream("fuzz-failure.bin", std::ios::binary).write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  std::fprintf(stderr, "fuzz: an accepted input breaks a promise (%s); the input is in fuzz-failure.bin\n", why.c_str());
  std::abort();
}

// Every clip an importer accepts must be valid (Clip::validate).
template <class ClipT>
void require_valid(const ClipT& clip, const uint8_t* data, size_t size) {
  try {
    clip.validate();
  } catch (const std::exception& e) {
    fail_with_input(data, size, e.what());
  }
}

// Shared data files (relative to ../shared/data) as seeds, each cut to at most `max_bytes`
// (the fuzzer's mutations then produce truncated files too). Missing files are skipped.
inline std::vector<std::string> shared_files(const std::vector<std::string>& relative, std::size_t max_bytes) {
  std::vector<std::string> out;
  const auto dir = shared_data_dir();
  if (dir.empty()) return out;
  for (const auto& rel : relative) {
    std::ifstream in(dir / rel, std::ios::binary);
    if (!in) continue;
    std::stringstream ss;
    ss << in.rdbuf();
    std::string s = ss.str();
    if (s.size() > max_bytes) s.resize(max_bytes);
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace mimic::fuzz
