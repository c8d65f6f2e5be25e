#pragma once
// Errors mimic reports to its users. Every error about an input names the source (a file path or
// a label for in-memory text), the place in it (line, frame, key) and what is wrong.
#include <stdexcept>
#include <string>

namespace mimic {

// Any error mimic raises on purpose.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Malformed or unsupported input: "source:line: message" (line 0 = whole file, no line number).
class ParseError : public Error {
 public:
  ParseError(std::string source, int line, const std::string& message);
  const std::string& source() const { return source_; }
  int line() const { return line_; }

 private:
  std::string source_;
  int line_;
};

// A long computation stopped on request (Ctrl-C, SIGTERM): thrown from inside collection and
// learning loops, which poll a stop flag, and caught where the last completed state is kept.
class Interrupted : public Error {
 public:
  using Error::Error;
};

}  // namespace mimic
