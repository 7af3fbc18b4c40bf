#include <gtest/gtest.h>

#include <filesystem>

#include "radarslam/core/errors.h"
#include "radarslam/core/yaml_params.h"
#include "radarslam/frontend/odometry_params.h"

namespace radarslam {
namespace {

TEST(OdometryParams, YamlOverridesDefaults) {
  const YamlParams y = YamlParams::fromText(
      "cartesian: {size_px: 501}\nodometry: {keypoints: {detector: akaze}, outliers: {max_clique: false},\n"
      "  tracking: {motion_compensation: false}, keyframes: {max_translation_m: 2.0}}\n");
  OdometryParams p;
  loadParams(y, p);
  y.rejectUnknownKeys();
  EXPECT_EQ(p.cartesian.size_px, 501);
  EXPECT_EQ(p.keypoints.detector, "akaze");
  EXPECT_FALSE(p.outliers.max_clique);
  EXPECT_FALSE(p.tracking.motion_compensation);
  EXPECT_EQ(p.keyframes.max_translation_m, 2.0);
  EXPECT_EQ(p.matching.radius_m, MatchParams{}.radius_m);  // untouched keys keep defaults
}

TEST(OdometryParams, TyposAndBadValuesAreErrors) {
  OdometryParams p;
  const YamlParams typo = YamlParams::fromText("odometry: {keyframes: {max_translation: 2}}\n", "cfg.yaml");
  loadParams(typo, p);
  EXPECT_THROW(typo.rejectUnknownKeys(), InputError);
  EXPECT_THROW(loadParams(YamlParams::fromText("odometry: {outliers: {consistency: maybe}}\n"), p),
               InputError);
  EXPECT_THROW(loadParams(YamlParams::fromText("odometry: {matching: {radius_m: -1}}\n"), p), InputError);
}

TEST(OdometryParams, DopplerSectionIsReadAndRangeChecked) {
  OdometryParams p;
  EXPECT_FALSE(p.doppler.enabled);  // off unless a sensor config enables it
  const YamlParams y = YamlParams::fromText("odometry: {doppler: {enabled: true, beta_s: -0.03}}\n");
  loadParams(y, p);
  y.rejectUnknownKeys();
  EXPECT_TRUE(p.doppler.enabled);
  EXPECT_DOUBLE_EQ(p.doppler.beta_s, -0.03);
  EXPECT_THROW(loadParams(YamlParams::fromText("odometry: {doppler: {beta_s: 2}}\n"), p), InputError);
  // The sensors whose beta is not published ship with the compensation off.
  for (const char* name : {"mulran", "boreas"}) {
    OdometryParams q;
    loadParams(YamlParams::fromFile(std::string(RADARSLAM_SOURCE_DIR) + "/config/" + name + ".yaml"), q);
    EXPECT_FALSE(q.doppler.enabled) << name;
  }
}

TEST(OdometryParams, MotionPriorIsReadAndItsGateRangeChecked) {
  OdometryParams p;
  EXPECT_TRUE(p.refine.motion_prior);
  const YamlParams y =
      YamlParams::fromText("odometry: {refine: {motion_prior: false, motion_prior_chi2: 7.81}}\n");
  loadParams(y, p);
  y.rejectUnknownKeys();
  EXPECT_FALSE(p.refine.motion_prior);
  EXPECT_DOUBLE_EQ(p.refine.motion_prior_chi2, 7.81);
  EXPECT_THROW(loadParams(YamlParams::fromText("odometry: {refine: {motion_prior_chi2: 0}}\n"), p),
               InputError);
  EXPECT_THROW(loadParams(YamlParams::fromText("odometry: {refine: {motion_prior: maybe}}\n"), p),
               InputError);
}

TEST(OdometryParams, EveryShippedConfigLoads) {
  int n = 0;
  for (const char* name : {"oxford", "mulran", "boreas", "radiate", "sim_radar"}) {
    const auto path = std::filesystem::path(RADARSLAM_SOURCE_DIR) / "config" / (std::string(name) + ".yaml");
    SCOPED_TRACE(path.string());
    const YamlParams y = YamlParams::fromFile(path.string());
    OdometryParams p;
    EXPECT_NO_THROW(loadParams(y, p));  // unknown keys: test/slam (the files also hold slam:)
    ++n;
  }
  EXPECT_EQ(n, 5);
}

}  // namespace
}  // namespace radarslam
