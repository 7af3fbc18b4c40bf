// Regression tests for inputs found by the sanitizers / fuzzers (docs/hardening.md): stamp text
// whose nanosecond count does not fit in int64 is "not a stamp", never an exception or overflow.
#include <gtest/gtest.h>

#include "radarslam/core/time.h"

using namespace radarslam;

TEST(TimeRegressionsFuzz, DigitStampsThatOverflowInt64AreRejected) {
  StampNs t = 0;
  // 19 digits above INT64_MAX: std::stoll threw std::out_of_range (escaped every parser).
  EXPECT_FALSE(parseStampByDigits("9999999999999999999", t));
  // 10 (s), 13 (ms), 16 (us) digits whose ns count overflows: signed overflow (UBSan).
  EXPECT_FALSE(parseStampByDigits("9999999999", t));
  EXPECT_FALSE(parseStampByDigits("9999999999999", t));
  EXPECT_FALSE(parseStampByDigits("9999999999999999", t));
  // The largest values that fit are still stamps.
  ASSERT_TRUE(parseStampByDigits("9223372036854775807", t));
  EXPECT_EQ(t, 9223372036854775807LL);
  ASSERT_TRUE(parseStampByDigits("9223372036854775", t));  // us
  EXPECT_EQ(t, 9223372036854775000LL);
  ASSERT_TRUE(parseStampByDigits("9223372036", t));  // s
  EXPECT_EQ(t, 9223372036000000000LL);
}

TEST(TimeRegressionsFuzz, SecondsDotFractionThatOverflowsInt64IsRejected) {
  StampNs t = 0;
  EXPECT_FALSE(parseSecondsDotFraction("9999999999.5", t));  // signed overflow before the fix
  ASSERT_TRUE(parseSecondsDotFraction("1574859771.5", t));
  EXPECT_EQ(t, 1574859771000000005LL);  // RADIATE's unpadded ns field: ".5" = 5 ns
}
