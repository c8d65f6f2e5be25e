#include "core/error.hpp"

namespace mimic {

static std::string format_parse_error(const std::string& source, int line, const std::string& msg) {
  if (line > 0) return source + ":" + std::to_string(line) + ": " + msg;
  return source + ": " + msg;
}

ParseError::ParseError(std::string source, int line, const std::string& message)
    : Error(format_parse_error(source, line, message)), source_(std::move(source)), line_(line) {}

}  // namespace mimic
