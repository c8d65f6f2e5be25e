// The down rule (env/down_rule) on hand-made root heights and ground contacts.
#include <gtest/gtest.h>

#include "env/down_rule.hpp"
#include "error_message.hpp"

using namespace mimic;
using test::error_of;

namespace {

TEST(DownRule, TenFramesBelowHalfTheStandingHeightAndNotACrouch) {
  DownRule rule(0.9);  // lying: below 0.45 m for 10 frames in a row
  // A deep crouch: the root at 0.5 m (above 0.45) for a long time is never down.
  for (int i = 0; i < 100; ++i) EXPECT_FALSE(rule.update(0.5));
  EXPECT_FALSE(rule.down());
  // Nine frames lying, one up: the count starts again.
  for (int i = 0; i < 9; ++i) EXPECT_FALSE(rule.update(0.2));
  EXPECT_FALSE(rule.update(0.46));
  for (int i = 0; i < 9; ++i) EXPECT_FALSE(rule.update(0.2));
  // The tenth frame in a row is the fall, said once.
  EXPECT_TRUE(rule.update(0.44));
  EXPECT_TRUE(rule.down());
  for (int i = 0; i < 20; ++i) EXPECT_FALSE(rule.update(0.1));
  EXPECT_TRUE(rule.down());
  // A bounce above the height while lying is no new fall: down until 10 frames in a row are above.
  for (int i = 0; i < 9; ++i) EXPECT_FALSE(rule.update(0.6));
  EXPECT_TRUE(rule.down());
  for (int i = 0; i < 5; ++i) EXPECT_FALSE(rule.update(0.1));
  EXPECT_TRUE(rule.down());
  for (int i = 0; i < 9; ++i) EXPECT_FALSE(rule.update(0.9));
  EXPECT_TRUE(rule.down());
  EXPECT_FALSE(rule.update(0.9));
  EXPECT_FALSE(rule.down());
  // Up again; a second fall is said again.
  for (int i = 0; i < 9; ++i) EXPECT_FALSE(rule.update(0.1));
  EXPECT_TRUE(rule.update(0.1));
  // A fall body on the ground is lying too, whatever the root's height (on a pile of cubes).
  DownRule contact(0.9);
  for (int i = 0; i < 9; ++i) EXPECT_FALSE(contact.update(0.8, true));
  EXPECT_TRUE(contact.update(0.8, true));
  // Another standing height and other settings.
  rule.restart(2.0);
  EXPECT_FALSE(rule.down());
  DownRule quick(1.0, 0.3, 2);
  EXPECT_FALSE(quick.update(0.31));
  EXPECT_FALSE(quick.update(0.29));
  EXPECT_TRUE(quick.update(0.29));
  EXPECT_NE(error_of([] { DownRule bad(1.0, 1.5, 10); }).find("fraction in (0, 1)"), std::string::npos);
  EXPECT_NE(error_of([] { DownRule bad(1.0, 0.5, 0); }).find("frames >= 1"), std::string::npos);
}

}  // namespace
