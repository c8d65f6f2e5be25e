#include <gtest/gtest.h>

#include <cmath>

#include "core/math.hpp"
#include "core/statistics.hpp"
#include "core/text_scanner.hpp"
#include "core/error.hpp"

using namespace mimic;

TEST(Math, EulerIntrinsicMatchesHandComputedMatrix) {
  // Rz(90deg) * Rx(90deg): X stays -> Y (z-turn); Y -> Z (x-turn) -> rotated by Rz -> Z.
  const double a[2] = {kPi / 2, kPi / 2};
  const Quat q = euler_intrinsic("ZX", a);
  EXPECT_TRUE((q * Vec3::UnitX()).isApprox(Vec3::UnitY(), 1e-12));
  EXPECT_TRUE((q * Vec3::UnitY()).isApprox(Vec3::UnitZ(), 1e-12));
  EXPECT_TRUE((q * Vec3::UnitZ()).isApprox(Vec3::UnitX(), 1e-12));
}

TEST(Math, RotvecRoundTripAndSmallAngles) {
  for (const Vec3& v : {Vec3(0.3, -0.2, 0.1), Vec3(0, 0, 3.0), Vec3(1e-14, 0, 0), Vec3(0, 0, 0)}) {
    EXPECT_TRUE(quat_to_rotvec(rotvec_to_quat(v)).isApprox(v, 1e-9) || v.norm() < 1e-12) << v.transpose();
  }
  // A rotation by pi/2 about z as a rotation vector.
  EXPECT_TRUE(quat_to_rotvec(axis_rotation('z', kPi / 2)).isApprox(Vec3(0, 0, kPi / 2), 1e-12));
}

TEST(Math, AngularVelocityOfConstantSpin) {
  const Quat q0 = axis_rotation('x', 0.1), q1 = axis_rotation('x', 0.4);
  EXPECT_TRUE(angular_velocity(q0, q1, 0.1).isApprox(Vec3(3.0, 0, 0), 1e-12));
}

TEST(Math, HeadingIgnoresPitchAndRoll) {
  const Quat q = axis_rotation('z', 0.7) * axis_rotation('y', 0.3) * axis_rotation('x', -0.2);
  EXPECT_NEAR(heading_angle(q), 0.7, 1e-12);
  EXPECT_NEAR(twist_angle(axis_rotation('y', -1.2), Vec3::UnitY()), -1.2, 1e-12);
}

TEST(TextScanner, ReportsLineNumbers) {
  TextScanner sc("a 1\n\nb x", "mem.txt");
  EXPECT_EQ(sc.next(), "a");
  EXPECT_EQ(sc.expect_double("one"), 1.0);
  EXPECT_EQ(sc.next(), "b");
  EXPECT_EQ(sc.line(), 3);
  try {
    sc.expect_double("a number");
    FAIL() << "no error";
  } catch (const ParseError& e) {
    EXPECT_EQ(e.line(), 3);
    EXPECT_STREQ(e.what(), "mem.txt:3: expected a number (a finite number), found 'x'");
  }
}

TEST(TextScanner, RejectsNonFiniteAndPartialNumbers) {
  double v = 0;
  EXPECT_FALSE(parse_double("nan", v));
  EXPECT_FALSE(parse_double("inf", v));
  EXPECT_FALSE(parse_double("1.5x", v));
  EXPECT_FALSE(parse_double("1e999", v));
  EXPECT_TRUE(parse_double("+2.5", v));
  EXPECT_EQ(v, 2.5);
}

TEST(Statistics, MeanAndPopulationStdOfASample) {
  EXPECT_DOUBLE_EQ(mimic::mean_of({1, 2, 3, 4}), 2.5);
  // deviations -1.5, -0.5, 0.5, 1.5: squares sum to 5, over 4 samples
  EXPECT_DOUBLE_EQ(mimic::std_of({1, 2, 3, 4}), std::sqrt(1.25));
  EXPECT_DOUBLE_EQ(mimic::std_of({7}), 0.0);
  EXPECT_TRUE(std::isnan(mimic::mean_of({})));
  EXPECT_TRUE(std::isnan(mimic::std_of({})));
}

TEST(Statistics, MedianIsTheMiddleValueOrTheMeanOfTheTwoMiddleOnes) {
  EXPECT_DOUBLE_EQ(mimic::median_of({5, 1, 100}), 5.0);    // unsorted, one far-off value
  EXPECT_DOUBLE_EQ(mimic::median_of({4, 1, 3, 2}), 2.5);   // (2 + 3) / 2
  EXPECT_DOUBLE_EQ(mimic::median_of({7}), 7.0);
  EXPECT_TRUE(std::isnan(mimic::median_of({})));
}
