#pragma once
// The table-driven harness of the malformed-input suites: each case mutates a small valid text,
// and parsing it must raise mimic::ParseError naming the source, the line and the problem, never
// another exception and never a crash.
#include <gtest/gtest.h>

#include <exception>
#include <functional>
#include <set>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.hpp"

namespace mimic::test {

struct MalformedCase {
  std::string what;
  std::string text;
  int line;  // expected ParseError::line(); 0 = the error names no line
  std::string expect_substring;
};

// `text` with the only occurrence of `from` replaced by `to`; a pattern that is missing or
// ambiguous throws, which fails the test (the table must mutate the base it says it mutates).
inline std::string replace_once(std::string text, std::string_view from, std::string_view to) {
  const std::size_t at = text.find(from);
  if (at == std::string::npos || text.find(from, at + 1) != std::string::npos)
    throw std::logic_error("pattern '" + std::string(from) + "' must occur exactly once");
  return text.replace(at, from.size(), to);
}

// The text up to (not including) the only occurrence of `marker`.
inline std::string cut_before(const std::string& text, std::string_view marker) {
  replace_once(text, marker, "");  // checks that the marker occurs exactly once
  return text.substr(0, text.find(marker));
}

// Checks every case of `cases`: names and texts are distinct and differ from `base`, and
// `parse(text)` throws a ParseError whose source is `source`, whose line is the case's line, whose
// message starts with "source:line: " ("source: " for line 0), contains the expected substring
// and is printable ASCII. A failure names its case.
inline void expect_parse_errors(const std::vector<MalformedCase>& cases, const std::string& base,
                                const std::string& source,
                                const std::function<void(const std::string& text)>& parse) {
  std::set<std::string> names, texts;
  for (const MalformedCase& c : cases) {
    SCOPED_TRACE(c.what);
    EXPECT_TRUE(names.insert(c.what).second) << "duplicate case name";
    EXPECT_TRUE(texts.insert(c.text).second) << "duplicate case text";
    EXPECT_NE(c.text, base);
    try {
      parse(c.text);
      ADD_FAILURE() << "parsed without error";
    } catch (const ParseError& e) {
      const std::string msg = e.what();
      const std::string prefix = source + (c.line > 0 ? ":" + std::to_string(c.line) + ": " : ": ");
      EXPECT_EQ(e.source(), source);
      EXPECT_EQ(e.line(), c.line) << msg;
      EXPECT_EQ(msg.rfind(prefix, 0), 0u) << msg;
      EXPECT_NE(msg.find(c.expect_substring), std::string::npos)
          << "message: " << msg << "\nwanted: " << c.expect_substring;
      for (const char ch : msg) EXPECT_TRUE(ch >= ' ' && ch <= '~') << "unprintable byte in: " << msg;
    } catch (const std::exception& e) {
      ADD_FAILURE() << "not a ParseError: " << e.what();
    }
  }
}

}  // namespace mimic::test
