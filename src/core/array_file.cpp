#include "core/array_file.hpp"

#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <set>

#include "core/error.hpp"

namespace mimic {

namespace {

constexpr char kMagic[8] = {'M', 'I', 'M', 'I', 'C', 'A', 'R', 'R'};
constexpr std::size_t kHeaderBytes = 24;
constexpr std::size_t kMaxNameBytes = 256;
constexpr int kMaxRank = 4;

template <class T>
void put(std::string& out, T value) {
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));  // little-endian hosts only (x86-64, AArch64): checked below
  out.append(reinterpret_cast<const char*>(bytes), sizeof(T));
}

static_assert(std::endian::native == std::endian::little, "the array file is little-endian; this host is not");

std::uint32_t crc_of(std::string_view bytes) {
  uLong crc = crc32(0L, Z_NULL, 0);
  std::size_t done = 0;
  while (done < bytes.size()) {  // zlib takes at most 4 GiB a call
    const auto n = static_cast<uInt>(std::min<std::size_t>(bytes.size() - done, 1u << 30));
    crc = crc32(crc, reinterpret_cast<const Bytef*>(bytes.data() + done), n);
    done += n;
  }
  return static_cast<std::uint32_t>(crc);
}

void check_name(const std::string& name) {
  if (name.empty() || name.size() > kMaxNameBytes) throw Error("array name must hold 1 to 256 characters");
  for (const char c : name)
    if (c < 33 || c > 126) throw Error("array name '" + name + "' holds a character that is not printable ASCII");
}

// Reads the file's values in order, refusing to step past its end.
class Reader {
 public:
  explicit Reader(std::string_view bytes) : bytes_(bytes) {}
  template <class T>
  T get(const char* what) {
    need(sizeof(T), what);
    T v;
    std::memcpy(&v, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return v;
  }
  std::string_view take(std::size_t n, const std::string& what) {
    need(n, what);
    const std::string_view s = bytes_.substr(at_, n);
    at_ += n;
    return s;
  }
  std::size_t left() const { return bytes_.size() - at_; }
  std::size_t at() const { return at_; }

 private:
  void need(std::size_t n, const std::string& what) const {
    if (n > left())
      throw Error("file ends inside " + what + " (at byte " + std::to_string(at_ + kHeaderBytes) + ", " + std::to_string(left()) +
                  " bytes left where " + std::to_string(n) + " are needed)");
  }
  std::string_view bytes_;
  std::size_t at_ = 0;
};

}  // namespace

std::size_t NamedArray::count() const {
  std::size_t n = 1;
  for (const std::uint32_t d : shape) n *= d;
  return n;
}

NamedArray NamedArray::of_text(std::string name, std::string text) {
  NamedArray a;
  a.name = std::move(name);
  a.kind = Kind::Text;
  a.shape = {static_cast<std::uint32_t>(text.size())};
  a.text = std::move(text);
  return a;
}

NamedArray NamedArray::of_floats(std::string name, std::vector<std::uint32_t> shape, std::vector<float> values) {
  NamedArray a = of_text(std::move(name), "");
  a.kind = Kind::Float32, a.shape = std::move(shape), a.f32 = std::move(values);
  return a;
}

NamedArray NamedArray::of_doubles(std::string name, std::vector<std::uint32_t> shape, std::vector<double> values) {
  NamedArray a = of_text(std::move(name), "");
  a.kind = Kind::Float64, a.shape = std::move(shape), a.f64 = std::move(values);
  return a;
}

NamedArray NamedArray::of_scalar(std::string name, double value) { return of_doubles(std::move(name), {}, {value}); }

std::string encode_arrays(const std::vector<NamedArray>& arrays) {
  std::string body;
  put<std::uint32_t>(body, static_cast<std::uint32_t>(arrays.size()));
  std::set<std::string> names;
  for (const NamedArray& a : arrays) {
    check_name(a.name);
    if (!names.insert(a.name).second) throw Error("array '" + a.name + "' is given twice");
    if (a.shape.size() > kMaxRank) throw Error("array '" + a.name + "' has rank " + std::to_string(a.shape.size()) + ", above 4");
    const std::size_t held = a.kind == NamedArray::Kind::Text ? a.text.size() : a.kind == NamedArray::Kind::Float32 ? a.f32.size() : a.f64.size();
    if (a.kind == NamedArray::Kind::Text ? a.shape.size() != 1 || a.shape[0] != held : held != a.count())
      throw Error("array '" + a.name + "' holds " + std::to_string(held) + " values where its shape holds " + std::to_string(a.count()));
    put<std::uint16_t>(body, static_cast<std::uint16_t>(a.name.size()));
    body += a.name;
    put<std::uint8_t>(body, static_cast<std::uint8_t>(a.kind));
    put<std::uint8_t>(body, static_cast<std::uint8_t>(a.shape.size()));
    for (const std::uint32_t d : a.shape) put<std::uint32_t>(body, d);
    if (a.kind == NamedArray::Kind::Text) body += a.text;
    else if (a.kind == NamedArray::Kind::Float32) body.append(reinterpret_cast<const char*>(a.f32.data()), a.f32.size() * sizeof(float));
    else body.append(reinterpret_cast<const char*>(a.f64.data()), a.f64.size() * sizeof(double));
  }
  std::string out(kMagic, sizeof kMagic);
  put<std::uint32_t>(out, kArrayFileVersion);
  put<std::uint32_t>(out, crc_of(body));
  put<std::uint64_t>(out, static_cast<std::uint64_t>(body.size()));
  return out + body;
}

std::vector<NamedArray> decode_arrays(std::string_view bytes) {
  if (bytes.size() < kHeaderBytes || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
    throw Error(bytes.size() < sizeof kMagic || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0
                    ? "not a mimic array file (it does not start with MIMICARR)"
                    : "file ends inside its 24-byte header");
  std::uint32_t version = 0, crc = 0;
  std::uint64_t size = 0;
  std::memcpy(&version, bytes.data() + 8, 4);
  std::memcpy(&crc, bytes.data() + 12, 4);
  std::memcpy(&size, bytes.data() + 16, 8);
  if (version != kArrayFileVersion)
    throw Error("format version " + std::to_string(version) + ", where this build reads version " + std::to_string(kArrayFileVersion) +
                (version > kArrayFileVersion ? " (written by a newer mimic: update mimic, or export the model again with this one)" : ""));
  const std::string_view body = bytes.substr(kHeaderBytes);
  if (size != body.size())
    throw Error("the header says " + std::to_string(size) + " bytes follow it, the file has " + std::to_string(body.size()) +
                (body.size() < size ? " (cut short)" : " (bytes were added)"));
  if (crc_of(body) != crc) throw Error("the CRC-32 of its contents does not match the one it was written with: the file is damaged");
  Reader r(body);
  const auto n = r.get<std::uint32_t>("the entry count");
  std::vector<NamedArray> out;
  std::set<std::string> names;
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::string entry = "entry " + std::to_string(i + 1);
    NamedArray a;
    const auto name_size = r.get<std::uint16_t>("a name's length");
    a.name = std::string(r.take(name_size, entry + "'s name"));
    check_name(a.name);
    if (!names.insert(a.name).second) throw Error("array '" + a.name + "' is given twice");
    const auto kind = r.get<std::uint8_t>("a kind");
    if (kind > 2) throw Error("array '" + a.name + "': kind " + std::to_string(kind) + " (0 text, 1 float32, 2 float64)");
    a.kind = static_cast<NamedArray::Kind>(kind);
    const auto rank = r.get<std::uint8_t>("a rank");
    if (rank > kMaxRank) throw Error("array '" + a.name + "' has rank " + std::to_string(rank) + ", above 4");
    if (a.kind == NamedArray::Kind::Text && rank != 1) throw Error("array '" + a.name + "' is text of rank " + std::to_string(rank) + ", not 1");
    std::size_t count = 1;
    for (int d = 0; d < rank; ++d) {
      a.shape.push_back(r.get<std::uint32_t>("a shape"));
      count *= a.shape.back();
      if (count > r.left()) throw Error("array '" + a.name + "' has a shape larger than the file");
    }
    const std::size_t width = a.kind == NamedArray::Kind::Text ? 1 : a.kind == NamedArray::Kind::Float32 ? sizeof(float) : sizeof(double);
    const std::string_view data = r.take(count * width, "array '" + a.name + "'s values");
    if (a.kind == NamedArray::Kind::Text) a.text = std::string(data);
    else if (a.kind == NamedArray::Kind::Float32) a.f32.resize(count);
    else a.f64.resize(count);
    // An array with a zero in its shape holds no values; memcpy's pointers must not be null even
    // for zero bytes, and an empty vector's data() may be.
    if (count > 0 && a.kind == NamedArray::Kind::Float32) std::memcpy(a.f32.data(), data.data(), data.size());
    if (count > 0 && a.kind == NamedArray::Kind::Float64) std::memcpy(a.f64.data(), data.data(), data.size());
    out.push_back(std::move(a));
  }
  if (r.left() != 0) throw Error(std::to_string(r.left()) + " bytes after the last of its " + std::to_string(n) + " arrays");
  return out;
}

}  // namespace mimic
