// Real data: the 10 consecutive Oxford Radar RobotCar scan pairs of the tiny sample, tracked with
// the shipped config/oxford.yaml, against the dataset's ground-truth relative motion (interpolated
// at each scan's reference time, where the Oxford GT rows are stamped).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <numeric>

#include "radarslam/core/yaml_params.h"
#include "radarslam/frontend/odometry.h"
#include "radarslam/io/dataset.h"
#include "shared_data.h"

namespace radarslam {
namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

TEST(OxfordPairs, MedianRelativeMotionErrorBeatsTarget) {
  RADARSLAM_REQUIRE_REAL_DATA(dir, "oxford_radar_robotcar_tiny");
  const auto reader = openDataset(dir);
  ASSERT_EQ(reader->size(), 11u);
  OdometryParams params;
  loadParams(YamlParams::fromFile(std::string(RADARSLAM_SOURCE_DIR) + "/config/oxford.yaml"), params);
  RadarOdometry odo(params);
  std::vector<double> err_m, err_deg;
  std::optional<mrpt::math::TPose2D> prev_gt;
  for (std::size_t i = 0; i < reader->size(); ++i) {
    const auto scan = reader->readScan(i);
    const OdometryStep step = odo.process(*scan);
    const auto gt = reader->groundTruthAt(scan->refStampNs());
    ASSERT_TRUE(gt);
    if (i > 0) {
      EXPECT_EQ(step.status, TrackingStatus::Tracking) << "scan " << i;
      const mrpt::math::TPose2D truth = *gt - *prev_gt;
      err_m.push_back(std::hypot(step.motion.x - truth.x, step.motion.y - truth.y));
      err_deg.push_back(std::abs(std::remainder(step.motion.phi - truth.phi, 2 * std::numbers::pi)) * 180 /
                        std::numbers::pi);
    }
    prev_gt = gt;
  }
  ASSERT_EQ(err_m.size(), 10u);
  std::printf("Oxford 10 pairs: median %.4f m %.4f deg, mean %.4f m\n", median(err_m), median(err_deg),
              std::accumulate(err_m.begin(), err_m.end(), 0.0) / 10);
  // Targets: 0.05 m and 0.08 deg (yeti: 0.060-0.073 m, 0.096-0.111 deg). Measured 0.048 m, 0.049 deg.
  EXPECT_LE(median(err_m), 0.05);
  EXPECT_LE(median(err_deg), 0.06);
  EXPECT_LT(*std::max_element(err_m.begin(), err_m.end()), 0.2);
}

}  // namespace
}  // namespace radarslam
