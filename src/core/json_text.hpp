#pragma once
// Pieces of JSON text for the files mimic writes.
#include <string>
#include <string_view>

namespace mimic {

// `s` as a JSON string: quoted, quotes and backslashes escaped, control characters as \uXXXX.
std::string json_quoted(std::string_view s);

}  // namespace mimic
