#include <gtest/gtest.h>

#include "radarslam/core/time.h"

using namespace radarslam;

TEST(Time, ParsesStampsByDigitCount) {
  StampNs t = 0;
  ASSERT_TRUE(parseStampByDigits("1547131046353776", t));  // Oxford, us
  EXPECT_EQ(t, 1547131046353776000LL);
  ASSERT_TRUE(parseStampByDigits("1628184886551599081", t));  // Boreas 2021-08-05, ns
  EXPECT_EQ(t, 1628184886551599081LL);
  ASSERT_TRUE(parseStampByDigits("0001547131010502681", t));  // Oxford gps.csv, zero-padded us
  EXPECT_EQ(t, 1547131010502681000LL);
  EXPECT_FALSE(parseStampByDigits("12a4", t));
  EXPECT_FALSE(parseStampByDigits("", t));
  EXPECT_FALSE(parseStampByDigits("-5", t));
}

TEST(Time, ParsesRadiateSecondsWithUnpaddedNanoseconds) {
  StampNs t = 0;
  ASSERT_TRUE(parseSecondsDotFraction("1574859771.744660272", t));
  EXPECT_EQ(t, 1574859771744660272LL);
  ASSERT_TRUE(parseSecondsDotFraction("1574859771.44660272", t));  // 8 digits: 0.044660272 s
  EXPECT_EQ(t, 1574859771044660272LL);
  EXPECT_FALSE(parseSecondsDotFraction("1574859771.1234567890", t));
  EXPECT_FALSE(parseSecondsDotFraction("abc.5", t));
}

TEST(Time, MrptClockRoundTripKeeps100nsTicks) {
  const StampNs t = 1547131046353776123LL;
  EXPECT_EQ(fromMrptTime(toMrptTime(t)), t / 100 * 100);
  EXPECT_NEAR(mrpt::Clock::toDouble(toMrptTime(t)), 1547131046.353776, 1e-6);
}
