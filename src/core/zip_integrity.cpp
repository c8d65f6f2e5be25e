#include "core/zip_integrity.hpp"

#include <zlib.h>

#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>

#include "core/error.hpp"

namespace mimic {

namespace {

constexpr std::uint32_t kEndOfDirectory = 0x06054b50, kZip64End = 0x06064b50, kZip64Locator = 0x07064b50;
constexpr std::uint32_t kDirectoryEntry = 0x02014b50, kLocalHeader = 0x04034b50;
constexpr std::uint32_t kZip64Extra = 0x0001;
constexpr std::uint64_t kStored = 0, kDeflated = 8;

// Little-endian reads that refuse to leave the buffer.
class Reader {
 public:
  explicit Reader(std::string_view bytes) : b_(bytes) {}
  std::uint64_t read(std::size_t at, int width, const char* what) const {
    if (at > b_.size() || static_cast<std::size_t>(width) > b_.size() - at)
      throw Error(std::string("zip archive is damaged: its ") + what + " lies outside the file");
    std::uint64_t v = 0;
    for (int i = width - 1; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(b_[at + static_cast<std::size_t>(i)]);
    return v;
  }
  std::size_t size() const { return b_.size(); }
  std::string_view slice(std::size_t at, std::size_t n, const std::string& what) const {
    if (at > b_.size() || n > b_.size() - at) throw Error("zip archive is damaged: " + what + " lies outside the file");
    return b_.substr(at, n);
  }

 private:
  std::string_view b_;
};

// A deflated entry's data (LibTorch deflates its small code entries), of exactly `size` bytes.
std::string inflate_entry(std::string_view deflated, std::uint64_t size, const std::string& name) {
  const std::string damaged = "zip archive entry '" + name + "' is damaged: ";
  if (size > (std::uint64_t{1} << 30)) throw Error(damaged + "a compressed entry of " + std::to_string(size) + " bytes");
  if (deflated.size() > std::numeric_limits<uInt>::max()) throw Error(damaged + "its compressed data is too long");
  std::string out(static_cast<std::size_t>(size), '\0');
  z_stream z{};
  if (inflateInit2(&z, -MAX_WBITS) != Z_OK) throw Error("zlib: cannot start inflating");
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(deflated.data()));
  z.avail_in = static_cast<uInt>(deflated.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  const int status = inflate(&z, Z_FINISH);
  const uLong produced = z.total_out;
  inflateEnd(&z);
  if (status != Z_STREAM_END || produced != size) throw Error(damaged + "its compressed data does not inflate to its recorded size");
  return out;
}

// The end-of-directory record: searched back from the end over the longest comment a zip may have.
std::size_t find_end_record(const Reader& r) {
  if (r.size() < 22) throw Error("not a zip archive (" + std::to_string(r.size()) + " bytes)");
  const std::size_t lowest = r.size() > 22 + 65535 ? r.size() - 22 - 65535 : 0;
  for (std::size_t at = r.size() - 22;; --at) {
    if (r.read(at, 4, "end record") == kEndOfDirectory) return at;
    if (at == lowest) break;
  }
  throw Error("zip archive is truncated or damaged: its end record is missing (" + std::to_string(r.size()) + " bytes)");
}

}  // namespace

ZipSummary verify_zip(std::string_view bytes) {
  const Reader r(bytes);
  const std::size_t end = find_end_record(r);
  std::uint64_t entries = r.read(end + 10, 2, "end record");
  std::uint64_t directory_size = r.read(end + 12, 4, "end record");
  std::uint64_t directory_at = r.read(end + 16, 4, "end record");
  // ZIP64 (LibTorch writes it): the real counts live in a record the locator before the end points to.
  if (end >= 20 && r.read(end - 20, 4, "zip64 locator") == kZip64Locator) {
    const std::uint64_t at = r.read(end - 20 + 8, 8, "zip64 locator");
    if (at > r.size() || r.read(static_cast<std::size_t>(at), 4, "zip64 end record") != kZip64End)
      throw Error("zip archive is damaged: its zip64 end record is missing");
    entries = r.read(static_cast<std::size_t>(at) + 32, 8, "zip64 end record");
    directory_size = r.read(static_cast<std::size_t>(at) + 40, 8, "zip64 end record");
    directory_at = r.read(static_cast<std::size_t>(at) + 48, 8, "zip64 end record");
  }
  if (directory_at > r.size() || directory_size > r.size() - directory_at)
    throw Error("zip archive is truncated or damaged: its directory lies outside the file");
  ZipSummary summary;
  std::size_t at = static_cast<std::size_t>(directory_at);
  for (std::uint64_t i = 0; i < entries; ++i) {
    if (r.read(at, 4, "directory") != kDirectoryEntry)
      throw Error("zip archive is damaged: directory entry " + std::to_string(i + 1) + " of " + std::to_string(entries) +
                  " is not where its directory says");
    const auto method = r.read(at + 10, 2, "directory");
    const auto crc = static_cast<std::uint32_t>(r.read(at + 16, 4, "directory"));
    std::uint64_t compressed = r.read(at + 20, 4, "directory"), size = r.read(at + 24, 4, "directory");
    const auto name_length = static_cast<std::size_t>(r.read(at + 28, 2, "directory"));
    const auto extra_length = static_cast<std::size_t>(r.read(at + 30, 2, "directory"));
    const auto comment_length = static_cast<std::size_t>(r.read(at + 32, 2, "directory"));
    std::uint64_t local = r.read(at + 42, 4, "directory");
    const std::string name(r.slice(at + 46, name_length, "a directory entry's name"));
    // Sizes and offsets too large for 32 bits are in the entry's zip64 extra field, in this order.
    for (std::size_t e = at + 46 + name_length; e + 4 <= at + 46 + name_length + extra_length;) {
      const auto id = r.read(e, 2, "directory"), length = static_cast<std::size_t>(r.read(e + 2, 2, "directory"));
      if (id == kZip64Extra) {
        std::size_t f = e + 4;
        if (size == 0xFFFFFFFF) size = r.read(f, 8, "zip64 field"), f += 8;
        if (compressed == 0xFFFFFFFF) compressed = r.read(f, 8, "zip64 field"), f += 8;
        if (local == 0xFFFFFFFF) local = r.read(f, 8, "zip64 field");
      }
      e += 4 + length;
    }
    if (method != kStored && method != kDeflated)
      throw Error("zip archive entry '" + name + "' is compressed by method " + std::to_string(method) + ", which LibTorch never writes");
    if (method == kStored && compressed != size) throw Error("zip archive entry '" + name + "' is damaged: stored with two different sizes");
    if (local > r.size() || r.read(static_cast<std::size_t>(local), 4, "local header") != kLocalHeader)
      throw Error("zip archive entry '" + name + "' is damaged: its header is not where the directory says");
    const auto l = static_cast<std::size_t>(local);
    const std::size_t data_at = l + 30 + static_cast<std::size_t>(r.read(l + 26, 2, "local header")) + static_cast<std::size_t>(r.read(l + 28, 2, "local header"));
    const std::string_view stored = r.slice(data_at, static_cast<std::size_t>(compressed), "entry '" + name + "''s data");
    std::string inflated;
    if (method == kDeflated) inflated = inflate_entry(stored, size, name);
    const std::string_view data = method == kDeflated ? std::string_view(inflated) : stored;
    // zlib's crc32 takes at most 4 GiB a call.
    uLong computed = crc32(0L, Z_NULL, 0);
    for (std::size_t done = 0; done < data.size();) {
      const std::size_t n = std::min<std::size_t>(data.size() - done, 1u << 30);
      computed = crc32(computed, reinterpret_cast<const Bytef*>(data.data() + done), static_cast<uInt>(n));
      done += n;
    }
    if (static_cast<std::uint32_t>(computed) != crc) {
      char crcs[64];
      std::snprintf(crcs, sizeof crcs, "recorded %08x, now %08x", crc, static_cast<std::uint32_t>(computed));
      throw Error("zip archive entry '" + name + "' is damaged: its data fails the CRC-32 recorded when it was written (" + crcs + ")");
    }
    ++summary.entries;
    summary.data_bytes += data.size();
    at += 46 + name_length + extra_length + comment_length;
  }
  return summary;
}

}  // namespace mimic
