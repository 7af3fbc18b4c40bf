// The checks a YAML text passes before MRPT's parser sees it: nesting depth (the parser recurses
// per level), binary/control bytes and UTF-8 validity; and what YamlParams makes of them.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "radarslam/core/errors.h"
#include "radarslam/core/yaml_params.h"
#include "radarslam/core/yaml_text_check.h"

namespace radarslam {
namespace {

std::string nested(std::size_t n, const std::string& open, const std::string& close,
                   const std::string& leaf) {
  std::string s;
  for (std::size_t i = 0; i < n; ++i) s += open;
  s += leaf;
  for (std::size_t i = 0; i < n; ++i) s += close;
  return s;
}

std::string blockNested(std::size_t n) {
  std::string s;
  for (std::size_t i = 0; i < n; ++i) s += std::string(2 * i, ' ') + "a:\n";
  return s + std::string(2 * n, ' ') + "b: 1\n";
}

TEST(YamlDepth, CountsFlowBracketsBlockIndentationAndDashes) {
  EXPECT_EQ(yamlNestingDepth(""), 0u);
  EXPECT_EQ(yamlNestingDepth("a: 1\nb: 2\n"), 1u);
  EXPECT_EQ(yamlNestingDepth("x: " + nested(10, "[", "]", "1")), 11u);
  EXPECT_EQ(yamlNestingDepth(nested(10, "{a: ", "}", "1")), 11u);
  EXPECT_EQ(yamlNestingDepth(blockNested(10)), 11u);
  EXPECT_EQ(yamlNestingDepth("- - - - x\n"), 5u);
  // Multi-line flow collections and dedent back to the top level.
  EXPECT_EQ(yamlNestingDepth("a: [1,\n  [2,\n   3]]\nb: 1\n"), 3u);
  EXPECT_EQ(yamlNestingDepth("a:\n  b:\n    c: 1\nd: 1\n"), 3u);
}

TEST(YamlDepth, IgnoresBracketsInQuotesCommentsAndPlainScalars) {
  EXPECT_EQ(yamlNestingDepth("a: '[[[[[['\n"), 1u);
  EXPECT_EQ(yamlNestingDepth("a: \"[[[\\\"[[[\"\n"), 1u);
  EXPECT_EQ(yamlNestingDepth("a: 1  # [[[[[[\n# {{{{\n"), 1u);
  EXPECT_EQ(yamlNestingDepth("a: x[[[[y\nb: it's [1]\n"), 2u);
}

TEST(YamlDepth, StopsEarlyOnHugeInputs) {
  const std::string deep = "x: " + nested(200000, "[", "]", "1");
  EXPECT_GT(yamlNestingDepth(deep), kMaxYamlDepth);
  EXPECT_LE(yamlNestingDepth(deep), kMaxYamlDepth + 2);
  EXPECT_THROW(checkYamlText(deep, "deep.yaml"), InputError);
  EXPECT_NO_THROW(checkYamlText("x: " + nested(kMaxYamlDepth - 1, "[", "]", "1"), "ok.yaml"));
}

TEST(YamlDepth, DeepTextsAreOneLineErrorsNotStackOverflows) {
  for (const std::string& text : {"x: " + nested(20000, "[", "]", "1"), nested(20000, "{a: ", "}", "1"),
                                  nested(20000, "- ", "", "1"), blockNested(2000)}) {
    try {
      YamlParams::fromText(text, "deep.yaml");
      FAIL() << "expected an error";
    } catch (const InputError& e) {
      EXPECT_EQ(e.where(), "deep.yaml");
      EXPECT_NE(e.problem().find("nested more than 64"), std::string::npos) << e.what();
    }
  }
}

TEST(YamlBinary, DetectsNulControlBytesAndInvalidUtf8) {
  EXPECT_EQ(yamlTextProblem("a: 1\tb\r\n# \xC3\xA9t\xC3\xA9 \xE2\x82\xAC \xF0\x9F\x98\x80\n"), "");
  EXPECT_NE(yamlTextProblem(std::string("a: 1\n\0", 6)).find("NUL byte at line 2"), std::string::npos);
  EXPECT_NE(yamlTextProblem("a: \x07\n").find("control byte 0x07"), std::string::npos);
  EXPECT_NE(yamlTextProblem("a: \xff\n").find("UTF-8"), std::string::npos);
  EXPECT_NE(yamlTextProblem("a: \xC3\n").find("UTF-8"), std::string::npos);          // truncated
  EXPECT_NE(yamlTextProblem("a: \xC0\xAF\n").find("UTF-8"), std::string::npos);      // overlong
  EXPECT_NE(yamlTextProblem("a: \xED\xA0\x80\n").find("UTF-8"), std::string::npos);  // surrogate
}

TEST(YamlParamsText, SyntaxErrorsAreOneLineWithLineAndColumn) {
  for (const auto& [text, where] :
       {std::pair<std::string, std::string>{"a: [1, 2\nb: 3\n", "line 3, column 1"},
        {"a: {b: 1\n", "line 2, column 1"},
        {"a: 1\n  b: 2\n c: 3\n", "line 1, column 4"}}) {
    try {
      YamlParams::fromText(text, "bad.yaml");
      FAIL() << "expected an error for " << text;
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
      EXPECT_NE(e.problem().find(where), std::string::npos) << e.what();
    }
  }
}

TEST(YamlParamsText, EmptyIsDefaultsButAScalarOrNullIsAnError) {
  EXPECT_NO_THROW(YamlParams::fromText("", "e.yaml"));
  EXPECT_NO_THROW(YamlParams::fromText("# just a comment\n\n", "e.yaml"));
  EXPECT_NO_THROW(
      YamlParams::fromText("\xEF\xBB\xBF"
                           "a: 1\n",
                           "bom.yaml"));
  EXPECT_THROW(YamlParams::fromText("~\n", "n.yaml"), InputError);
  EXPECT_THROW(YamlParams::fromText("null\n", "n.yaml"), InputError);
  EXPECT_THROW(YamlParams::fromText("hello\n", "s.yaml"), InputError);
  EXPECT_THROW(YamlParams::fromText("- 1\n", "l.yaml"), InputError);
  EXPECT_THROW(YamlParams::fromText(std::string("a: 1\0", 5), "z.yaml"), InputError);
}

TEST(YamlRange, ContainsAndText) {
  EXPECT_TRUE(Range::closed(0, 1).contains(0));
  EXPECT_TRUE(Range::closed(0, 1).contains(1));
  EXPECT_FALSE(Range::above(0, 1).contains(0));
  EXPECT_FALSE(Range::closed(0, 1).contains(std::nan("")));
  EXPECT_FALSE(Range::closed(0, 1).contains(HUGE_VAL));
  EXPECT_EQ(Range::closed(0, 1).text(), "[0, 1]");
  EXPECT_EQ(Range::above(0, 1e5).text(), "(0, 100000]");
}

TEST(YamlRange, GettersRejectOutOfRangeNamingTheDottedKey) {
  const auto p =
      YamlParams::fromText("s:\n  i: 1e9\n  d: -0.5\n  n: nan\n  z: 2.5\n  ok: 3\n  l: [1, 200]\n", "r.yaml");
  const auto s = p.section("s");
  int i = 5;
  double d = 1.0;
  std::size_t z = 1;
  long ok = 0;
  std::vector<double> l;
  auto expectKey = [](const auto& fn, const std::string& key) {
    try {
      fn();
      FAIL() << "expected an error for " << key;
    } catch (const InputError& e) {
      EXPECT_EQ(e.where(), "r.yaml");
      EXPECT_NE(e.problem().find("'" + key + "'"), std::string::npos) << e.what();
    }
  };
  expectKey([&] { s.get("i", i, Range::closed(1, 100)); }, "s.i");
  expectKey([&] { s.get("d", d, Range::above(0, 10)); }, "s.d");
  expectKey([&] { s.get("n", d, Range::closed(-1e9, 1e9)); }, "s.n");
  expectKey([&] { s.get("z", z, Range::closed(0, 10)); }, "s.z");  // not an integer
  expectKey([&] { s.get("l", l, Range::closed(0, 100), 10); }, "s.l");
  expectKey([&] { s.get("l", l, Range::closed(0, 1000), 1); }, "s.l");
  EXPECT_EQ(i, 5);  // unchanged on error
  EXPECT_EQ(d, 1.0);
  s.get("ok", ok, Range::closed(1, 3));
  EXPECT_EQ(ok, 3);
  s.get("missing", i, Range::closed(100, 200));  // absent: the default is kept, unchecked
  EXPECT_EQ(i, 5);
  expectKey([&] { s.fail("x", "bad"); }, "s.x");
}

}  // namespace
}  // namespace radarslam
