#pragma once
// Errors mimic reports to its users. Every error about an input names the source (a file path or
// a label for in-memory text), the place in it (line, frame, key) and what is wrong.
#include <stdexcept>
#include <string>
#include <utility>

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

// A value that is wrong for the object it configures, found by that object (not by a parser):
// `key` names the configuration key (e.g. "max_drift"), so that a config reader can point at
// the line that set it. what() is "'key' message".
class KeyError : public Error {
 public:
  KeyError(std::string key, std::string message) : Error("'" + key + "' " + message), key_(std::move(key)), message_(std::move(message)) {}
  const std::string& key() const { return key_; }
  const std::string& message() const { return message_; }  // without the key

 private:
  std::string key_, message_;
};

// A long computation stopped on request (Ctrl-C, SIGTERM): thrown from inside collection and
// learning loops, which poll a stop flag, and caught where the last completed state is kept.
class Interrupted : public Error {
 public:
  using Error::Error;
};

}  // namespace mimic
