#include <gtest/gtest.h>

#include "radarslam/core/errors.h"
#include "radarslam/core/yaml_params.h"

using namespace radarslam;

TEST(YamlParams, OverridesDefaultsAndTypeChecks) {
  const auto p = YamlParams::fromText("a: 2.5\nsec:\n  n: 7\n  flag: true\n  name: oxford\n", "t.yaml");
  double a = 1.0, missing = 3.0;
  int n = 0;
  bool flag = false;
  std::string name;
  p.get("a", a);
  p.get("missing", missing);
  const auto s = p.section("sec");
  s.get("n", n);
  s.get("flag", flag);
  s.get("name", name);
  EXPECT_EQ(a, 2.5);
  EXPECT_EQ(missing, 3.0);
  EXPECT_EQ(n, 7);
  EXPECT_TRUE(flag);
  EXPECT_EQ(name, "oxford");
  EXPECT_NO_THROW(p.rejectUnknownKeys());
}

TEST(YamlParams, UnknownKeyIsAnErrorNamingFileAndKey) {
  const auto p = YamlParams::fromText("sec:\n  keyframe_distnace: 2\n", "cfg.yaml");
  double d = 0;
  p.section("sec").get("keyframe_distance", d);
  try {
    p.rejectUnknownKeys();
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "cfg.yaml");
    EXPECT_NE(std::string(e.what()).find("sec.keyframe_distnace"), std::string::npos);
  }
}

TEST(YamlParams, WrongTypeIsAnError) {
  const auto p = YamlParams::fromText("n: seven\n", "cfg.yaml");
  int n = 0;
  EXPECT_THROW(p.get("n", n), InputError);
  EXPECT_THROW(YamlParams::fromFile("/nonexistent/cfg.yaml"), InputError);
}
