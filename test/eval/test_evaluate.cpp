// evaluate(): association by time, dropped counts, input checks; the JSON report, the summary and
// the plots it produces.
#include <gtest/gtest.h>
#include <mrpt/containers/yaml.h>
#include <opencv2/imgcodecs.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <sstream>

#include "file_contents.h"
#include "radarslam/core/errors.h"
#include "radarslam/eval/evaluate.h"
#include "radarslam/eval/plots.h"
#include "radarslam/eval/report.h"
#include "synthetic.h"
#include "temp_dir.h"

using namespace radarslam;
using namespace radarslam::eval;
using mrpt::math::TPose2D;

namespace {

using radarslam::test::readFileBytes;
/// Constant velocity 10 m/s along a 30 deg line, ground truth at 10 Hz from t = 0 to 100 s.
TPose2D lineAt(StampNs t) {
  const double s = 10.0 * toSeconds(t), a = std::numbers::pi / 6;
  return {s * std::cos(a), s * std::sin(a), a};
}
Trajectory lineGroundTruth() {
  Trajectory gt;
  for (StampNs t = 0; t <= 100 * kNsPerSec; t += 100'000'000) gt.push_back({t, lineAt(t)});
  return gt;
}
/// Estimates at 4 Hz from -1 s to 101.5 s, offset 37 ms from the ground-truth samples.
Trajectory lineEstimate() {
  Trajectory est;
  for (StampNs t = -kNsPerSec + 37'000'000; t <= 101'500'000'000LL; t += 250'000'000)
    est.push_back({t, lineAt(t)});
  return est;
}
}  // namespace

TEST(Evaluate, InterpolatesGroundTruthAtEstimateStampsAndCountsDrops) {
  const Trajectory gt = lineGroundTruth(), est = lineEstimate();
  const EvalReport r = evaluate(est, gt);
  // Stamps -0.963, -0.713, -0.463, -0.213 s precede the ground truth; 100.037 .. 101.287 s follow it.
  EXPECT_EQ(r.association.dropped_before_gt, 4u);
  EXPECT_EQ(r.association.dropped_after_gt, 6u);
  EXPECT_EQ(r.association.dropped_in_gt_gaps, 0u);
  EXPECT_EQ(r.association.size(), est.size() - 10);
  EXPECT_EQ(r.est_poses, est.size());
  EXPECT_EQ(r.gt_poses, gt.size());
  // Linear motion: interpolation is exact, so every error vanishes.
  EXPECT_LT(r.ate.trans_m.max, 1e-9);
  EXPECT_LT(r.rpe.trans_m.max, 1e-9);
  ASSERT_TRUE(r.kitti.valid());
  EXPECT_LT(r.kitti.t_err_percent, 1e-9);
  EXPECT_NEAR(r.gt_path_length_m,
              10.0 * toSeconds(r.association.stamps.back() - r.association.stamps.front()), 1e-6);
}

TEST(Evaluate, DropsEstimatesInsideGroundTruthGaps) {
  Trajectory gt;
  for (const auto& p : lineGroundTruth())
    if (p.stamp <= 50 * kNsPerSec || p.stamp >= 55 * kNsPerSec) gt.push_back(p);  // a 5 s hole
  const EvalReport r = evaluate(lineEstimate(), gt);
  EXPECT_EQ(r.association.dropped_in_gt_gaps, 20u);  // 50.037 .. 54.787 s at 4 Hz
  EvalParams wide;
  wide.max_gt_gap_s = 6.0;
  EXPECT_EQ(evaluate(lineEstimate(), gt, wide).association.dropped_in_gt_gaps, 0u);
}

TEST(Evaluate, RejectsUnusableInput) {
  const Trajectory gt = lineGroundTruth();
  Trajectory shuffled = lineEstimate();
  std::swap(shuffled[5], shuffled[6]);
  try {
    evaluate(shuffled, gt, {}, "est.txt");
    FAIL() << "accepted non-increasing stamps";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "est.txt");
  }
  Trajectory late = lineEstimate();
  for (auto& p : late) p.stamp += 1000 * kNsPerSec;
  EXPECT_THROW(evaluate(late, gt), InputError);
  Trajectory nan = lineEstimate();
  nan[3].pose.x = std::nan("");
  EXPECT_THROW(evaluate(nan, gt), InputError);
}

TEST(Evaluate, LoadsParametersFromYaml) {
  EvalParams p;
  loadParams(YamlParams::fromText("kitti_lengths_m: [50, 100]\nkitti_step_frames: 1\nmax_gt_gap_s: 0.5\n"),
             p);
  EXPECT_EQ(p.kitti.lengths_m, (std::vector<double>{50, 100}));
  EXPECT_EQ(p.kitti.step_frames, 1u);
  EXPECT_DOUBLE_EQ(p.max_gt_gap_s, 0.5);
  EXPECT_THROW(loadParams(YamlParams::fromText("kitti_step_frames: 0\n"), p), InputError);
}

TEST(Report, JsonCarriesTheMetricsAndNullForMissingOnes) {
  const Trajectory gt = test::windingDrive(1200);
  const EvalReport r = evaluate(test::scaled(gt, 1.02), gt, {}, "est \"quoted\".txt", "gt.txt");
  test::TempDir dir;
  writeJsonReport(dir / "report.json", r);
  const auto doc = mrpt::containers::yaml::FromText(readFileBytes(dir / "report.json"));  // JSON is YAML
  EXPECT_EQ(doc["estimate"]["label"].as<std::string>(), "est \"quoted\".txt");
  EXPECT_EQ(doc["association"]["matched"].as<int>(), 1200);
  EXPECT_NEAR(doc["kitti"]["t_err_percent"].as<double>(), r.kitti.t_err_percent, 1e-8);
  EXPECT_NEAR(doc["kitti"]["r_err_deg_per_100m"].as<double>(), r.kitti.r_err_deg_per_100m, 1e-8);
  EXPECT_EQ(doc["kitti"]["per_length"].asSequence().size(), 8u);
  EXPECT_NEAR(doc["ate"]["trans_m"]["rmse"].as<double>(), r.ate.trans_m.rmse, 1e-8);
  EXPECT_NEAR(doc["rpe"]["rot_deg"]["mean"].as<double>(), r.rpe.rot_deg.mean, 1e-8);

  const EvalReport short_run = evaluate(test::straightLine(20, 1.0), test::straightLine(20, 1.0));
  const std::string json = toJson(short_run);
  EXPECT_NE(json.find("\"t_err_percent\": null"), std::string::npos);
}

TEST(Report, SummaryShowsTheHeadlineNumbers) {
  const Trajectory gt = test::windingDrive(1200);
  const EvalReport r = evaluate(test::scaled(gt, 1.02), gt);
  const std::string s = formatSummary(r);
  char expected[32];
  std::snprintf(expected, sizeof(expected), "%.3f %%", r.kitti.t_err_percent);
  EXPECT_NE(s.find(expected), std::string::npos) << s;
  EXPECT_NE(s.find("ATE"), std::string::npos);
  EXPECT_NE(s.find("RPE"), std::string::npos);
  EXPECT_NE(formatSummary(evaluate(test::straightLine(20, 1.0), test::straightLine(20, 1.0)))
                .find("KITTI          n/a"),
            std::string::npos);
}

TEST(Plots, WritesSvgAndPngThatShowTheTrajectories) {
  const Trajectory gt = test::windingDrive(1200);
  Trajectory est = test::chain(1200, [](std::size_t k) {
    return TPose2D(2.03, 0.0, 0.05 * std::sin(0.013 * static_cast<double>(k)) + 2e-4);
  });
  const EvalReport r = evaluate(est, gt, {}, "runs/est.txt", "data/gt.txt");
  test::TempDir dir;
  const auto files = writePlots(dir / "plots", r);
  ASSERT_EQ(files.size(), 4u);
  for (const auto& f : files) ASSERT_TRUE(std::filesystem::exists(f)) << f;

  const std::string svg = readFileBytes(dir / "plots/trajectory.svg");
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_NE(svg.find("<polyline"), std::string::npos);
  EXPECT_NE(svg.find("x [m]"), std::string::npos);
  EXPECT_NE(svg.find("est.txt"), std::string::npos);
  EXPECT_NE(readFileBytes(dir / "plots/segment_errors.svg").find("segment length [m]"), std::string::npos);

  const cv::Mat img = cv::imread((dir / "plots/trajectory.png").string(), cv::IMREAD_COLOR);
  ASSERT_FALSE(img.empty());
  EXPECT_GT(img.cols, 1000);
  // White background, and the blue estimate (31, 119, 180) drawn in many pixels.
  EXPECT_EQ(img.at<cv::Vec3b>(2, 2), cv::Vec3b(255, 255, 255));
  int blue = 0;
  for (int y = 0; y < img.rows; ++y)
    for (int x = 0; x < img.cols; ++x) {
      const cv::Vec3b p = img.at<cv::Vec3b>(y, x);
      blue += std::abs(p[0] - 180) < 20 && std::abs(p[1] - 119) < 20 && std::abs(p[2] - 31) < 20;
    }
  EXPECT_GT(blue, 2000);
  const cv::Mat bars = cv::imread((dir / "plots/segment_errors.png").string(), cv::IMREAD_COLOR);
  ASSERT_FALSE(bars.empty());
}
