#pragma once
// mimic's own file of named arrays: what `mimic export` writes for the torch-free runtime
// (networks.mimic: weights, normaliser statistics, shapes and names). Small, documented and
// checked, so that a program without LibTorch reads it and a damaged file is refused.
//
// Layout (every number little-endian; docs/runtime.md):
//   bytes 0-7    magic "MIMICARR"
//   bytes 8-11   uint32 format version (kArrayFileVersion)
//   bytes 12-15  uint32 CRC-32 (zlib's) of every byte after byte 23
//   bytes 16-23  uint64 number of bytes after byte 23
//   then         uint32 entry count, and per entry:
//                  uint16 name length, the name (printable ASCII, unique)
//                  uint8 kind (0 text, 1 float32, 2 float64), uint8 rank (0-4), uint32 per dimension
//                  the values: rank 0 one value, else the product of the dimensions, row-major
//                  (text: rank 1, its bytes)
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace mimic {

inline constexpr std::uint32_t kArrayFileVersion = 1;

struct NamedArray {
  enum class Kind : std::uint8_t { Text = 0, Float32 = 1, Float64 = 2 };
  std::string name;
  Kind kind = Kind::Float32;
  std::vector<std::uint32_t> shape;  // empty: a scalar
  std::string text;                  // Kind::Text
  std::vector<float> f32;            // Kind::Float32
  std::vector<double> f64;           // Kind::Float64

  static NamedArray of_text(std::string name, std::string text);
  static NamedArray of_floats(std::string name, std::vector<std::uint32_t> shape, std::vector<float> values);
  static NamedArray of_doubles(std::string name, std::vector<std::uint32_t> shape, std::vector<double> values);
  static NamedArray of_scalar(std::string name, double value);
  std::size_t count() const;  // values the shape holds (1 for a scalar)
};

// The file's bytes. Error on a name that is empty, too long, not printable or repeated, a rank
// above 4, or values that do not fill the shape.
std::string encode_arrays(const std::vector<NamedArray>& arrays);
// The arrays of a file's bytes, in file order. Error (without the file's name: callers add it)
// on the first problem: a bad magic, a newer version, a cut or extended file, a CRC-32 that does
// not match, a name or shape that is not allowed, values past the end, bytes left over.
std::vector<NamedArray> decode_arrays(std::string_view bytes);

}  // namespace mimic
