#pragma once
// Whole-file reads with a size limit, and durable atomic writes (to a temporary beside the
// target, flushed to the disk, renamed over it, the directory flushed too), so that neither a
// crash nor a power loss leaves a half-written file where a good one was.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace mimic {

// What a reader takes at most, in bytes. MIMIC_MAX_INPUT_MB (a number of MiB) replaces every
// limit at once, for the user whose files really are that large.
inline constexpr std::uintmax_t kMiB = std::uintmax_t{1} << 20;
inline constexpr std::uintmax_t kMaxTextBytes = 256 * kMiB;        // clips, CSV, maps: any text
inline constexpr std::uintmax_t kMaxYamlBytes = 16 * kMiB;         // YAML and JSON: yaml-cpp holds ~60x a file in memory
inline constexpr std::uintmax_t kMaxCheckpointBytes = 4096 * kMiB; // checkpoints and models
// `limit`, or MIMIC_MAX_INPUT_MB's value where that is set (an Error where it is not a positive number).
std::uintmax_t input_limit(std::uintmax_t limit);
// Throws Error "<source>: <size>, above the <limit> this reader takes ..." when size > limit.
void check_input_size(std::uintmax_t size, std::uintmax_t limit, const std::string& source, const char* what);

// Reads a whole file of at most `max_bytes` (read in pieces: a device or pipe that never ends is
// refused at the limit); throws Error naming the path if it cannot, or if the file is larger.
std::string read_text_file(const std::filesystem::path& path, std::uintmax_t max_bytes = kMaxTextBytes);

// Writes `content` to `path` atomically and durably; creates missing parent directories. The
// temporary is `path` + ".tmp<pid>"; an error removes it and leaves `path` as it was.
void write_file_atomic(const std::filesystem::path& path, std::string_view content);
// The same where `path` already exists: its old content moves to `previous` (atomically too), so
// that the last two versions are on disk at every moment.
void write_file_atomic_keeping(const std::filesystem::path& path, const std::filesystem::path& previous, std::string_view content);

// Removes the temporaries (`*.tmp<digits>`) an interrupted write_file_atomic left in `dir`;
// returns how many. Call it only where no other process is writing (a run's own directory).
int remove_stale_temporaries(const std::filesystem::path& dir);

// Where the shared data lives: $MIMIC_DATA if set, else ../shared/data relative to the source
// tree or the current directory; empty when none exists.
std::filesystem::path shared_data_dir();

}  // namespace mimic
