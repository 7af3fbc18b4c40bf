// InputError's message is one printable line whatever the input held, and exceptions that are not
// ours are described in one line too (docs/hardening.md).
#include <gtest/gtest.h>

#include <new>
#include <stdexcept>
#include <string>

#include "radarslam/core/errors.h"

using namespace radarslam;

TEST(OneLine, EscapesControlCharactersAndInvalidUtf8) {
  EXPECT_EQ(oneLine("a\nb\tc\rd"), "a\\nb\\tc\\rd");
  EXPECT_EQ(oneLine(std::string("x\0y", 3)), "x\\x00y");
  EXPECT_EQ(oneLine("caf\xc3\xa9"), "caf\xc3\xa9");       // valid UTF-8 is kept
  EXPECT_EQ(oneLine("bad\xff\xfe"), "bad\\xff\\xfe");     // invalid bytes are escaped
  EXPECT_EQ(oneLine("\xc3"), "\\xc3");                    // truncated sequence
  EXPECT_EQ(oneLine("\xed\xa0\x80"), "\\xed\\xa0\\x80");  // UTF-16 surrogate
  EXPECT_EQ(oneLine("\xe0\x80\xaf"), "\\xe0\\x80\\xaf");  // overlong encoding
}

TEST(OneLine, CutsLongTextAtACharacterBoundary) {
  const std::string huge(20'000'000, 'z');
  const std::string line = oneLine(huge, 100);
  EXPECT_LT(line.size(), 140u);
  EXPECT_NE(line.find("(19999900 more bytes)"), std::string::npos) << line;
  std::string accents;
  for (int i = 0; i < 100; ++i) accents += "\xc3\xa9";
  const std::string cut = oneLine(accents, 51);
  EXPECT_EQ(cut.substr(0, 52), accents.substr(0, 52));  // 26 whole characters, none split
  EXPECT_EQ(cut.find("\\x"), std::string::npos);
}

TEST(InputErrorMessage, IsOneLineWithWhereAndProblem) {
  const InputError e("dir/\xff.csv", "bad line 'x\ny" + std::string(5000, 'q') + "'");
  const std::string what = e.what();
  EXPECT_EQ(what.find('\n'), std::string::npos);
  EXPECT_EQ(what.rfind("dir/\\xff.csv: bad line 'x\\ny", 0), 0u) << what;
  EXPECT_LT(what.size(), 500u);
  EXPECT_EQ(e.where(), "dir/\xff.csv");  // the raw values stay available
}

TEST(DescribeException, OurOwnAndOthersInOneLine) {
  EXPECT_EQ(describeException(InputError("f.yaml", "bad key")), "f.yaml: bad key");
  EXPECT_NE(describeException(std::bad_alloc()).find("out of memory"), std::string::npos);
  const std::runtime_error cv(
      "OpenCV(4.6.0) /build/opencv/modules/core/src/matrix.cpp:250: error: (-215:Assertion failed) "
      "s >= 0 in function 'setSize'\n");
  EXPECT_EQ(describeException(cv),
            "internal error in OpenCV: (-215:Assertion failed) s >= 0 in function 'setSize'");
  EXPECT_EQ(describeException(std::runtime_error("first\nsecond")), "first");
}
