#include "core/tensorboard.hpp"

#include <array>
#include <bit>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <fcntl.h>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <utility>
#include <unistd.h>

#include "core/error.hpp"
#include "core/file_io.hpp"

namespace mimic {
namespace fs = std::filesystem;

namespace {

constexpr std::array<uint32_t, 256> make_crc32c_table() {
  std::array<uint32_t, 256> table{};
  for (uint32_t i = 0; i < 256; ++i) {
    uint32_t c = i;
    for (int k = 0; k < 8; ++k) c = (c & 1u) ? (c >> 1) ^ 0x82F63B78u : c >> 1;
    table[i] = c;
  }
  return table;
}

constexpr std::array<uint32_t, 256> kCrc32cTable = make_crc32c_table();

// TFRecord stores CRCs rotated and offset, so a CRC of data that itself holds CRCs stays useful.
uint32_t masked_crc(std::string_view data) {
  const uint32_t crc = crc32c(data);
  return ((crc >> 15) | (crc << 17)) + 0xa282ead8u;
}

// --- little-endian and protobuf encoding -------------------------------------------------------

void put_fixed(std::string& out, uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xffu));
}

void put_varint(std::string& out, uint64_t v) {
  while (v >= 0x80u) {
    out.push_back(static_cast<char>((v & 0x7fu) | 0x80u));
    v >>= 7;
  }
  out.push_back(static_cast<char>(v));
}

enum WireType : uint32_t { kVarint = 0, kFixed64 = 1, kLengthDelimited = 2, kFixed32 = 5 };

void put_key(std::string& out, uint32_t field, WireType type) {
  put_varint(out, (static_cast<uint64_t>(field) << 3) | type);
}

void put_bytes_field(std::string& out, uint32_t field, std::string_view bytes) {
  put_key(out, field, kLengthDelimited);
  put_varint(out, bytes.size());
  out.append(bytes);
}

// Event.wall_time (1, double), always written so every event carries its time.
void put_wall_time(std::string& out, double wall_time) {
  put_key(out, 1, kFixed64);
  put_fixed(out, std::bit_cast<uint64_t>(wall_time), 8);
}

double now_seconds() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

std::string host_name() {
  std::array<char, 256> buf{};
  if (::gethostname(buf.data(), buf.size() - 1) != 0 || buf[0] == '\0') return "localhost";
  std::string name(buf.data());
  for (char& c : name)
    if (c == '/') c = '_';  // never a path separator in the file name
  return name;
}

// Creates a file that did not exist (O_EXCL), so two writers never share one, even within a
// second or across processes. Returns false if the name is taken.
bool create_new_file(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) {
    if (errno == EEXIST) return false;
    throw Error(path.string() + ": cannot create: " + std::strerror(errno));
  }
  ::close(fd);
  return true;
}

// --- decoding ----------------------------------------------------------------------------------

uint64_t get_fixed(std::string_view s, size_t pos, int bytes) {
  uint64_t v = 0;
  for (int i = 0; i < bytes; ++i)
    v |= static_cast<uint64_t>(static_cast<uint8_t>(s[pos + static_cast<size_t>(i)])) << (8 * i);
  return v;
}

// A malformed protobuf message; the reader adds the file and record index.
struct MalformedEvent : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Reads one protobuf message field by field.
class ProtoReader {
 public:
  explicit ProtoReader(std::string_view data) : data_(data) {}
  bool done() const { return pos_ >= data_.size(); }

  uint64_t varint() {
    uint64_t v = 0;
    for (int shift = 0; shift < 64; shift += 7) {
      if (done()) throw MalformedEvent("truncated varint");
      const auto byte = static_cast<uint8_t>(data_[pos_++]);
      v |= static_cast<uint64_t>(byte & 0x7fu) << shift;
      if ((byte & 0x80u) == 0) return v;
    }
    throw MalformedEvent("varint longer than 10 bytes");
  }

  uint64_t fixed(int bytes) {
    const auto n = static_cast<size_t>(bytes);
    if (data_.size() - pos_ < n) throw MalformedEvent("truncated fixed-width field");
    const uint64_t v = get_fixed(data_, pos_, bytes);
    pos_ += n;
    return v;
  }

  std::string_view bytes() {
    const uint64_t n = varint();
    if (n > data_.size() - pos_) throw MalformedEvent("length-delimited field overruns its message");
    const std::string_view v = data_.substr(pos_, static_cast<size_t>(n));
    pos_ += static_cast<size_t>(n);
    return v;
  }

  void skip(uint32_t type) {
    switch (type) {
      case kVarint: varint(); return;
      case kFixed64: fixed(8); return;
      case kLengthDelimited: bytes(); return;
      case kFixed32: fixed(4); return;
      default: throw MalformedEvent("unsupported wire type " + std::to_string(type));
    }
  }

 private:
  std::string_view data_;
  size_t pos_ = 0;
};

// Appends the scalar of a Summary.Value {tag = 1, simple_value = 2}, if it has one.
void decode_value(std::string_view data, int64_t step, std::vector<TensorBoardScalar>& out) {
  ProtoReader r(data);
  std::string tag;
  bool has_value = false;
  float value = 0.0f;
  while (!r.done()) {
    const uint64_t key = r.varint();
    const auto field = key >> 3;
    const auto type = static_cast<uint32_t>(key & 7u);
    if (field == 1 && type == kLengthDelimited) {
      tag = std::string(r.bytes());
    } else if (field == 2 && type == kFixed32) {
      value = std::bit_cast<float>(static_cast<uint32_t>(r.fixed(4)));
      has_value = true;
    } else {
      r.skip(type);
    }
  }
  if (has_value) out.push_back({std::move(tag), static_cast<double>(value), step});
}

// Scalars of one Event {wall_time = 1, step = 2, summary = 5 {repeated value = 1}}. Fields may
// come in any order, so values are collected first and given the step at the end.
void decode_event(std::string_view data, std::vector<TensorBoardScalar>& out) {
  ProtoReader r(data);
  int64_t step = 0;
  std::vector<std::string_view> values;
  while (!r.done()) {
    const uint64_t key = r.varint();
    const auto field = key >> 3;
    const auto type = static_cast<uint32_t>(key & 7u);
    if (field == 2 && type == kVarint) {
      step = static_cast<int64_t>(r.varint());
    } else if (field == 5 && type == kLengthDelimited) {
      ProtoReader summary(r.bytes());
      while (!summary.done()) {
        const uint64_t skey = summary.varint();
        const auto stype = static_cast<uint32_t>(skey & 7u);
        if ((skey >> 3) == 1 && stype == kLengthDelimited) {
          values.push_back(summary.bytes());
        } else {
          summary.skip(stype);
        }
      }
    } else {
      r.skip(type);
    }
  }
  for (std::string_view v : values) decode_value(v, step, out);
}

// Event.step (field 2), 0 where absent.
int64_t event_step(std::string_view data) {
  ProtoReader r(data);
  int64_t step = 0;
  while (!r.done()) {
    const uint64_t key = r.varint();
    const auto type = static_cast<uint32_t>(key & 7u);
    if ((key >> 3) == 2 && type == kVarint) step = static_cast<int64_t>(r.varint());
    else r.skip(type);
  }
  return step;
}

}  // namespace

uint32_t crc32c(std::string_view data) {
  uint32_t crc = 0xffffffffu;
  for (const char c : data) crc = kCrc32cTable[(crc ^ static_cast<uint8_t>(c)) & 0xffu] ^ (crc >> 8);
  return ~crc;
}

std::string encode_scalar_event(const std::string& tag, double value, int64_t step,
                                double wall_time) {
  std::string v;  // Summary.Value
  put_bytes_field(v, 1, tag);
  put_key(v, 2, kFixed32);
  put_fixed(v, std::bit_cast<uint32_t>(static_cast<float>(value)), 4);
  std::string summary;
  put_bytes_field(summary, 1, v);

  std::string event;
  put_wall_time(event, wall_time);
  put_key(event, 2, kVarint);
  put_varint(event, static_cast<uint64_t>(step));  // negative steps: 10-byte two's complement
  put_bytes_field(event, 5, summary);
  return event;
}

TensorBoardWriter::TensorBoardWriter(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw Error(dir.string() + ": cannot create directory: " + ec.message());

  const auto seconds = std::chrono::duration_cast<std::chrono::seconds>(
                           std::chrono::system_clock::now().time_since_epoch())
                           .count();
  const std::string base = "events.out.tfevents." + std::to_string(seconds) + "." + host_name() +
                           "." + std::to_string(::getpid());
  for (int n = 0;; ++n) {
    if (n == 10000) throw Error((dir / base).string() + ": no free event file name");
    path_ = dir / (n == 0 ? base : base + "." + std::to_string(n));
    if (create_new_file(path_)) break;
  }

  out_.open(path_, std::ios::binary | std::ios::app);
  if (!out_) {
    const std::string reason = std::strerror(errno);
    fs::remove(path_, ec);
    throw Error(path_.string() + ": cannot open for writing: " + reason);
  }

  // TensorBoard expects the first event to name the format version.
  std::string event;
  put_wall_time(event, now_seconds());
  put_bytes_field(event, 3, "brain.Event:2");
  write_record(event);
}

TensorBoardWriter::~TensorBoardWriter() {
  if (out_.is_open()) out_.flush();  // errors cannot be reported from a destructor
}

void TensorBoardWriter::scalar(const std::string& tag, double value, int64_t step) {
  write_record(encode_scalar_event(tag, value, step, now_seconds()));
}

void TensorBoardWriter::flush() {
  out_.flush();
  if (!out_) throw Error(path_.string() + ": write failed");
}

void TensorBoardWriter::write_record(std::string_view payload) {
  std::string header;
  put_fixed(header, payload.size(), 8);
  std::string record = header;
  put_fixed(record, masked_crc(header), 4);
  record.append(payload);
  put_fixed(record, masked_crc(payload), 4);
  out_.write(record.data(), static_cast<std::streamsize>(record.size()));
  if (!out_) throw Error(path_.string() + ": write failed");
}

int truncate_tensorboard_events(const fs::path& dir, int64_t last_step) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return 0;
  int removed = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().filename().string().rfind("events.out.tfevents.", 0) != 0) continue;
    const std::string data = read_text_file(entry.path());
    const std::string_view all(data);
    std::string kept;
    size_t pos = 0;
    int records = 0, kept_records = 0;
    while (all.size() - pos >= 16) {
      const std::string_view header = all.substr(pos, 8);
      if (static_cast<uint32_t>(get_fixed(all, pos + 8, 4)) != masked_crc(header)) break;
      const uint64_t length = get_fixed(all, pos, 8);
      if (length > all.size() - pos - 16) break;
      const std::string_view payload = all.substr(pos + 12, static_cast<size_t>(length));
      if (static_cast<uint32_t>(get_fixed(all, pos + 12 + payload.size(), 4)) != masked_crc(payload)) break;
      int64_t step = 0;
      try {
        step = event_step(payload);
      } catch (const MalformedEvent&) {
        break;
      }
      ++records;
      const size_t end = pos + 16 + payload.size();
      if (step <= last_step) kept.append(all.substr(pos, end - pos)), ++kept_records;
      pos = end;
    }
    // Records after a damaged one cannot be framed: they go with it.
    if (kept.size() == data.size()) continue;
    removed += records - kept_records + (pos < all.size() ? 1 : 0);
    write_file_atomic(entry.path(), kept);
  }
  return removed;
}

std::vector<TensorBoardScalar> read_tensorboard_scalars(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error(file.string() + ": cannot open for reading: " + std::strerror(errno));
  std::ostringstream ss;  // not istreambuf_iterator: GCC 12 -Wnull-dereference misfires on it
  ss << in.rdbuf();
  if (in.bad()) throw Error(file.string() + ": read failed");
  const std::string data = std::move(ss).str();

  std::vector<TensorBoardScalar> scalars;
  const std::string_view all(data);
  size_t pos = 0;
  for (size_t index = 0; pos < all.size(); ++index) {
    const auto fail = [&](const std::string& what) {
      return Error(file.string() + ": record " + std::to_string(index) + " (byte " +
                   std::to_string(pos) + "): " + what);
    };
    const size_t left = all.size() - pos;
    if (left < 12) throw fail("truncated header");
    const std::string_view header = all.substr(pos, 8);
    if (static_cast<uint32_t>(get_fixed(all, pos + 8, 4)) != masked_crc(header))
      throw fail("length CRC mismatch");
    const uint64_t length = get_fixed(all, pos, 8);
    if (left < 16 || length > left - 16) throw fail("truncated data (length " + std::to_string(length) + ")");
    const std::string_view payload = all.substr(pos + 12, static_cast<size_t>(length));
    const size_t crc_at = pos + 12 + payload.size();
    if (static_cast<uint32_t>(get_fixed(all, crc_at, 4)) != masked_crc(payload))
      throw fail("data CRC mismatch");
    try {
      decode_event(payload, scalars);
    } catch (const MalformedEvent& e) {
      throw fail(std::string("malformed event: ") + e.what());
    }
    pos = crc_at + 4;
  }
  return scalars;
}

}  // namespace mimic
