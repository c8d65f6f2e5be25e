#pragma once
// Whole-file reads and atomic writes (write to a temporary beside the target, then rename), so a
// crash never leaves a half-written file where a good one was.
#include <filesystem>
#include <string>
#include <string_view>

namespace mimic {

// Reads a whole file; throws Error naming the path if it cannot.
std::string read_text_file(const std::filesystem::path& path);

// Writes `content` to `path` atomically; creates missing parent directories.
void write_file_atomic(const std::filesystem::path& path, std::string_view content);

// Where the shared data lives: $MIMIC_DATA if set, else ../shared/data relative to the source
// tree or the current directory; empty when none exists.
std::filesystem::path shared_data_dir();

}  // namespace mimic
