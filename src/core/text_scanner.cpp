#include "core/text_scanner.hpp"

#include <charconv>
#include <cmath>

#include "core/error.hpp"

namespace mimic {

namespace {
bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }

}  // namespace

std::string printable_token(std::string_view token) {
  std::string out;
  for (char c : token.substr(0, 40)) {
    const auto u = static_cast<unsigned char>(c);
    out += (u >= 32 && u < 127) ? c : '?';
  }
  if (token.size() > 40) out += "...";
  return out;
}

bool parse_double(std::string_view token, double& out) {
  if (token.empty()) return false;
  const char* first = token.data();
  const char* last = first + token.size();
  if (*first == '+') ++first;  // from_chars rejects a leading '+'
  const auto [ptr, ec] = std::from_chars(first, last, out);
  return ec == std::errc() && ptr == last && std::isfinite(out);
}

bool parse_long(std::string_view token, long& out) {
  if (token.empty()) return false;
  const char* first = token.data();
  const char* last = first + token.size();
  if (*first == '+') ++first;
  const auto [ptr, ec] = std::from_chars(first, last, out);
  return ec == std::errc() && ptr == last;
}

TextScanner::TextScanner(std::string_view text, std::string source)
    : text_(text), source_(std::move(source)) {}

void TextScanner::skip_space() {
  while (pos_ < text_.size()) {
    const char c = text_[pos_];
    if (c == '\n') {
      ++line_;
      ++pos_;
    } else if (is_space(c)) {
      ++pos_;
    } else if (comment_ != '\0' && c == comment_) {
      while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
    } else {
      break;
    }
  }
}

std::string_view TextScanner::next() {
  skip_space();
  const std::size_t start = pos_;
  while (pos_ < text_.size() && !is_space(text_[pos_])) ++pos_;
  return text_.substr(start, pos_ - start);
}

std::string_view TextScanner::peek() {
  skip_space();
  std::size_t end = pos_;
  while (end < text_.size() && !is_space(text_[end])) ++end;
  return text_.substr(pos_, end - pos_);
}

bool TextScanner::at_end() {
  skip_space();
  return pos_ >= text_.size();
}

std::string_view TextScanner::expect_token(std::string_view what) {
  std::string_view t = next();
  if (t.empty()) fail("unexpected end of file, expected " + std::string(what));
  return t;
}

void TextScanner::expect_word(std::string_view word) {
  std::string_view t = next();
  if (t.empty()) fail("unexpected end of file, expected '" + std::string(word) + "'");
  if (t != word) fail("expected '" + std::string(word) + "', found '" + printable_token(t) + "'");
}

double TextScanner::expect_double(std::string_view what) {
  std::string_view t = expect_token(what);
  double v = 0.0;
  if (!parse_double(t, v)) fail("expected " + std::string(what) + " (a finite number), found '" + printable_token(t) + "'");
  return v;
}

long TextScanner::expect_int(std::string_view what) {
  std::string_view t = expect_token(what);
  long v = 0;
  if (!parse_long(t, v)) fail("expected " + std::string(what) + " (an integer), found '" + printable_token(t) + "'");
  return v;
}

std::string_view TextScanner::rest_of_line() {
  while (pos_ < text_.size() && (text_[pos_] == ' ' || text_[pos_] == '\t' || text_[pos_] == '\r')) ++pos_;
  const std::size_t start = pos_;
  while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
  std::size_t end = pos_;
  while (end > start && is_space(text_[end - 1])) --end;
  return text_.substr(start, end - start);
}

void TextScanner::fail(const std::string& message) const { throw ParseError(source_, line_, message); }

void TextScanner::fail_at(int line, const std::string& message) const {
  throw ParseError(source_, line, message);
}

}  // namespace mimic
