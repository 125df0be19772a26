// Exact unit conversions between ubersim (SI) and the SSL protocols.
#include <gtest/gtest.h>

#include <cmath>

#include "ubersim/ssl_bridge/units.hpp"

using namespace ubersim::ssl;

TEST(SslUnits, MetresAndMillimetres) {
  EXPECT_DOUBLE_EQ(m_to_mm(1.2345), 1234.5);
  EXPECT_DOUBLE_EQ(m_to_mm(-4.5), -4500.0);
  EXPECT_DOUBLE_EQ(mm_to_m(1234.5), 1.2345);
  EXPECT_DOUBLE_EQ(mm_to_m(m_to_mm(0.0215)), 0.0215);
  EXPECT_EQ(m_to_whole_mm(9.0), 9000);
  EXPECT_EQ(m_to_whole_mm(0.0215), 22);  // 21.5 mm rounds away from zero
  EXPECT_EQ(m_to_whole_mm(-0.0015), -2);
}

TEST(SslUnits, DegreesAndRadians) {
  EXPECT_DOUBLE_EQ(deg_to_rad(180), M_PI);
  EXPECT_DOUBLE_EQ(deg_to_rad(45), M_PI / 4);
  EXPECT_DOUBLE_EQ(deg_to_rad(-90), -M_PI / 2);
  EXPECT_DOUBLE_EQ(rad_to_deg(M_PI / 6), 30.0);
  EXPECT_DOUBLE_EQ(rad_to_deg(deg_to_rad(37.5)), 37.5);
}

TEST(SslUnits, RpmAndRadiansPerSecond) {
  EXPECT_DOUBLE_EQ(rpm_to_rad_per_s(60), 2 * M_PI);  // one turn per second
  EXPECT_DOUBLE_EQ(rpm_to_rad_per_s(1000), 1000 * 2 * M_PI / 60);
  EXPECT_DOUBLE_EQ(rad_per_s_to_rpm(M_PI), 30.0);
  EXPECT_DOUBLE_EQ(rad_per_s_to_rpm(rpm_to_rad_per_s(-7500)), -7500.0);
}
