#include "core/file_io.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>

#include "core/build_paths.hpp"
#include "core/error.hpp"

namespace mimic {
namespace fs = std::filesystem;

namespace {

std::string megabytes(std::uintmax_t bytes) {
  if (bytes % kMiB == 0) return std::to_string(bytes / kMiB) + " MiB";
  char text[32];
  std::snprintf(text, sizeof text, "%.1f MiB", static_cast<double>(bytes) / static_cast<double>(kMiB));
  return text;
}

// Writes all of `data` to `fd`; false with errno set otherwise.
bool write_all(int fd, std::string_view data) {
  while (!data.empty()) {
    const ssize_t n = ::write(fd, data.data(), data.size());
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    data.remove_prefix(static_cast<std::size_t>(n));
  }
  return true;
}

// Flushes a directory's entries (a rename in it) to the disk; best effort where the file system
// cannot (some do not allow fsync on a directory).
void sync_directory(const fs::path& dir) {
  const int fd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  (void)::fsync(fd);
  ::close(fd);
}

// The temporary beside `path`, written and flushed; an Error (the temporary removed) otherwise.
fs::path write_temporary(const fs::path& path, std::string_view content) {
  if (path.has_parent_path()) {
    std::error_code ec;
    fs::create_directories(path.parent_path(), ec);
    if (ec) throw Error(path.parent_path().string() + ": cannot create the directory: " + ec.message());
  }
  fs::path tmp = path;
  tmp += ".tmp" + std::to_string(::getpid());
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw Error(tmp.string() + ": cannot open for writing: " + std::strerror(errno));
  const bool ok = write_all(fd, content) && ::fsync(fd) == 0;
  const int saved_errno = errno;
  if (::close(fd) != 0 || !ok) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw Error(tmp.string() + ": write failed: " + std::strerror(ok ? errno : saved_errno));
  }
  return tmp;
}

void rename_or_throw(const fs::path& from, const fs::path& to, const fs::path& tmp) {
  std::error_code ec;
  fs::rename(from, to, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw Error(to.string() + ": cannot replace: " + ec.message());
  }
}

}  // namespace

std::uintmax_t input_limit(std::uintmax_t limit) {
  const char* env = std::getenv("MIMIC_MAX_INPUT_MB");
  if (env == nullptr || *env == '\0') return limit;
  char* end = nullptr;
  const double mb = std::strtod(env, &end);
  if (end == env || *end != '\0' || !(mb > 0) || mb > 1e9) throw Error(std::string("MIMIC_MAX_INPUT_MB='") + env + "': expected a positive number of MiB");
  return static_cast<std::uintmax_t>(mb * static_cast<double>(kMiB));
}

void check_input_size(std::uintmax_t size, std::uintmax_t limit, const std::string& source, const char* what) {
  const std::uintmax_t max = input_limit(limit);
  if (size <= max) return;
  throw Error(source + ": more than " + megabytes(max) + ", the most this reader takes (" + what +
              "); set MIMIC_MAX_INPUT_MB to raise it");
}

std::string read_text_file(const fs::path& path, std::uintmax_t max_bytes) {
  const std::uintmax_t max = input_limit(max_bytes);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path.string() + ": cannot open for reading: " + std::strerror(errno));
  std::error_code ec;
  if (fs::is_regular_file(path, ec)) {
    const std::uintmax_t size = fs::file_size(path, ec);
    if (!ec) check_input_size(size, max_bytes, path.string(), "files of this kind");
  }
  // In pieces, whatever the file claims: a device or a pipe has no size to check first.
  std::string out;
  std::string piece(std::size_t{1} << 20, '\0');
  while (in) {
    in.read(piece.data(), static_cast<std::streamsize>(piece.size()));
    out.append(piece.data(), static_cast<std::size_t>(in.gcount()));
    if (out.size() > max) check_input_size(out.size(), max_bytes, path.string(), "files of this kind");
  }
  if (in.bad()) throw Error(path.string() + ": read failed");
  return out;
}

void write_file_atomic(const fs::path& path, std::string_view content) {
  const fs::path tmp = write_temporary(path, content);
  rename_or_throw(tmp, path, tmp);
  sync_directory(path.parent_path());
}

void write_file_atomic_keeping(const fs::path& path, const fs::path& previous, std::string_view content) {
  const fs::path tmp = write_temporary(path, content);
  std::error_code ec;
  if (fs::exists(path, ec)) {
    // A hard link first, so that `path` exists at every moment; then the new content over it.
    fs::remove(previous, ec);
    fs::create_hard_link(path, previous, ec);
    if (ec) {
      fs::remove(tmp, ec);
      throw Error(previous.string() + ": cannot keep the previous version: " + ec.message());
    }
  }
  rename_or_throw(tmp, path, tmp);
  sync_directory(path.parent_path());
}

int remove_stale_temporaries(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return 0;
  int removed = 0;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    const auto at = name.rfind(".tmp");
    if (at == std::string::npos || at + 4 == name.size()) continue;
    if (name.find_first_not_of("0123456789", at + 4) != std::string::npos) continue;
    if (fs::remove(entry.path(), ec)) ++removed;
  }
  return removed;
}

fs::path shared_data_dir() {
  if (const char* env = std::getenv("MIMIC_DATA"); env && *env) {
    if (fs::is_directory(env)) return fs::path(env);
    return {};
  }
  for (const fs::path& candidate : {fs::path(kSourceDir) / ".." / "shared" / "data",
                                    fs::current_path() / ".." / "shared" / "data",
                                    fs::current_path() / "shared" / "data"}) {
    std::error_code ec;
    if (fs::is_directory(candidate, ec)) return fs::weakly_canonical(candidate, ec);
  }
  return {};
}

}  // namespace mimic
