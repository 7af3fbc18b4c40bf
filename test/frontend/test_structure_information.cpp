// frontend/structure_information.h: a keypoint on an extended structure is known across it, not
// along it (point to line in eq. (4)); a compact target, or one elongated only along the beam's arc
// (the beam's own blur), keeps the isotropic weight. pose_refiner.h with those shapes: matches that
// slide along their line (they move with the sensor) no longer pull the pose along it.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include <cmath>

#include "radarslam/frontend/pose_refiner.h"
#include "radarslam/frontend/structure_information.h"

namespace radarslam {
namespace {

constexpr int kSize = 81;
constexpr double kMPerPx = 0.25;

/// A bright line through the image centre along unit `direction` (pixels), Gaussian across it.
cv::Mat lineImage(double dx, double dy) {
  cv::Mat im(kSize, kSize, CV_32F);
  const double c = kSize / 2;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const double across = -(x - c) * dy + (y - c) * dx;
      im.at<float>(y, x) = static_cast<float>(100 * std::exp(-across * across / (2 * 1.5 * 1.5)));
    }
  return im;
}

cv::Mat blobImage() {
  cv::Mat im(kSize, kSize, CV_32F);
  const double c = kSize / 2;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x)
      im.at<float>(y, x) =
          static_cast<float>(100 * std::exp(-((x - c) * (x - c) + (y - c) * (y - c)) / (2 * 1.5 * 1.5)));
  return im;
}

const cv::Point2f kCentre(kSize / 2, kSize / 2);
const Eigen::Matrix2d kScale = kMPerPx * Eigen::Matrix2d::Identity();

TEST(StructureInformation, ALineIsKnownAcrossItNotAlongIt) {
  // The line runs along x (radial: the keypoint is 20 m ahead), so its normal is y.
  const Eigen::Matrix2d w = structureInformation(lineImage(1, 0), kCentre, 6, kScale, {20, 0});
  EXPECT_NEAR(w(1, 1), 1.0, 1e-9);
  EXPECT_LT(w(0, 0), 0.05);
  EXPECT_NEAR(w(0, 1), 0.0, 1e-3);
}

TEST(StructureInformation, TheNormalFollowsThePixelToMetresMap) {
  // The converter's axes: metres x = -rows, metres y = -columns (a transposed, flipped image).
  Eigen::Matrix2d pixel_to_metres;
  pixel_to_metres << 0, -kMPerPx, -kMPerPx, 0;
  // Along the image's columns (pixel x) = along metres y; the keypoint 20 m to the left (y).
  const Eigen::Matrix2d w = structureInformation(lineImage(1, 0), kCentre, 6, pixel_to_metres, {0, 20});
  EXPECT_NEAR(w(0, 0), 1.0, 1e-9) << "known across the line, along metres x";
  EXPECT_LT(w(1, 1), 0.05);
}

TEST(StructureInformation, ACompactTargetKeepsTheIsotropicWeight) {
  const Eigen::Matrix2d w = structureInformation(blobImage(), kCentre, 6, kScale, {20, 5});
  EXPECT_GT(w(0, 0), 0.9);
  EXPECT_GT(w(1, 1), 0.9);
}

TEST(StructureInformation, AnElongationAlongTheBeamsArcIsTheBeamsBlur) {
  // The keypoint 20 m ahead, the streak across the bearing (along y): its normal is radial.
  EXPECT_TRUE(structureInformation(lineImage(0, 1), kCentre, 6, kScale, {20, 0}).isIdentity());
  // 40 degrees off the arc is a structure (tolerance 30 degrees).
  const double a = 40 * M_PI / 180;
  EXPECT_FALSE(
      structureInformation(lineImage(std::sin(a), std::cos(a)), kCentre, 6, kScale, {20, 0}).isIdentity());
}

TEST(StructureInformation, OutsideTheImageOrDisabledIsIsotropic) {
  EXPECT_TRUE(structureInformation(lineImage(1, 0), {3, 40}, 6, kScale, {20, 0}).isIdentity());
  StructureInformationParams off;
  off.enabled = false;
  EXPECT_TRUE(structureInformation(lineImage(1, 0), kCentre, 6, kScale, {20, 0}, off).isIdentity());
}

TEST(PoseRefiner, LineShapedMatchesDoNotPullAlongTheirLine) {
  const mrpt::math::TPose2D truth(2.0, 0.1, 0.01);
  Correspondences matches;
  std::vector<Eigen::Matrix2d> shapes;
  for (int i = 0; i < 20; ++i) {  // compact world points, matched where the truth puts them
    Correspondence m;
    m.cur = {-40.0 + 4.0 * i, (i % 2 ? 25.0 : -30.0) + i};
    const auto r = truth.composePoint({m.cur.x(), m.cur.y()});
    m.ref = {r.x, r.y};
    matches.push_back(m);
    shapes.push_back(Eigen::Matrix2d::Identity());
  }
  for (int i = 0; i < 40; ++i) {  // a wall along x at y = 10: the spots move with the sensor along it
    Correspondence m;
    m.cur = {-20.0 + i, 10.0};
    const auto r = truth.composePoint({m.cur.x(), m.cur.y()});
    m.ref = {m.cur.x(), r.y};  // right across the wall, no motion along it
    matches.push_back(m);
    shapes.push_back(Eigen::Vector2d(0, 1).asDiagonal());
  }
  RefineParams p;
  p.huber_m = 100;
  p.iterations = 30;
  const RefineResult pulled = refinePose(matches, {0, 0, 0}, p);
  const RefineResult shaped = refinePose(matches, {0, 0, 0}, p, shapes);
  EXPECT_GT(std::abs(pulled.pose.x - truth.x), 0.5) << "point to point: the wall holds the estimate back";
  EXPECT_NEAR(shaped.pose.x, truth.x, 1e-6);
  EXPECT_NEAR(shaped.pose.y, truth.y, 1e-6);
  EXPECT_NEAR(shaped.pose.phi, truth.phi, 1e-8);
}

}  // namespace
}  // namespace radarslam
