#pragma once
// A whitespace tokenizer over text that remembers line numbers, for the line-oriented motion
// formats (BVH, ASF, AMC). Every failure becomes a ParseError naming the source and line.
#include <string>
#include <string_view>

namespace mimic {

class TextScanner {
 public:
  TextScanner(std::string_view text, std::string source);

  // Next token, or empty at end of input. Skips whitespace (and '#' comments if enabled).
  std::string_view next();
  // Next token without consuming it.
  std::string_view peek();
  bool at_end();
  // Next token, which must exist; `what` describes what was expected.
  std::string_view expect_token(std::string_view what);
  // Next token, which must equal `word` (case-sensitive).
  void expect_word(std::string_view word);
  double expect_double(std::string_view what);
  long expect_int(std::string_view what);

  // Rest of the current line (after the last token read), trimmed; moves to the next line.
  std::string_view rest_of_line();

  void set_comment_char(char c) { comment_ = c; }
  int line() const { return line_; }
  const std::string& source() const { return source_; }
  [[noreturn]] void fail(const std::string& message) const;
  [[noreturn]] void fail_at(int line, const std::string& message) const;

 private:
  void skip_space();
  std::string_view text_;
  std::string source_;
  std::size_t pos_ = 0;
  int line_ = 1;
  char comment_ = '\0';
};

// Parses a whole token as a finite double; false if it is not one.
bool parse_double(std::string_view token, double& out);
bool parse_long(std::string_view token, long& out);

// A token made safe to quote in an error message (non-printables replaced, long ones cut).
std::string printable_token(std::string_view token);

}  // namespace mimic
