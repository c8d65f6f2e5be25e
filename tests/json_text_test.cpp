// JSON strings as mimic writes them.
#include "core/json_text.hpp"

#include <gtest/gtest.h>

using namespace mimic;

TEST(JsonText, QuotesAndEscapesQuotesBackslashesAndControlCharacters) {
  EXPECT_EQ(json_quoted("root"), "\"root\"");
  EXPECT_EQ(json_quoted("a\"b\\c"), "\"a\\\"b\\\\c\"");
  EXPECT_EQ(json_quoted("knee\tshape\n"), "\"knee\\u0009shape\\u000a\"");
  EXPECT_EQ(json_quoted(""), "\"\"");
}
