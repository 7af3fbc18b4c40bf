// SE(2) alignment, ATE and RPE against hand-computed cases.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "radarslam/eval/alignment.h"
#include "radarslam/eval/pose_errors.h"
#include "synthetic.h"

using namespace radarslam;
using namespace radarslam::eval;
using mrpt::math::TPoint2D;
using mrpt::math::TPose2D;
using test::posesOf;

TEST(PoseMath, Mrpt2DOperatorsAreComposeAndInverseCompose) {
  // The metric code relies on b - a = inv(a) (+) b.
  const TPose2D a(1, 2, 0.5), b(-3, 4, -1.2);
  const TPose2D rel = b - a;
  const TPose2D back = a + rel;
  EXPECT_NEAR(back.x, b.x, 1e-12);
  EXPECT_NEAR(back.y, b.y, 1e-12);
  EXPECT_NEAR(back.phi, b.phi, 1e-12);
}

TEST(Alignment, RecoversAKnownRigidTransform) {
  const TPose2D T(12.5, -7.25, 2.5);
  std::vector<TPoint2D> from, to;
  for (int i = 0; i < 20; ++i) {
    const TPoint2D p(std::cos(i * 0.7) * i, std::sin(i * 1.3) * 5.0);
    from.push_back(p);
    to.push_back(T + p);
  }
  const TPose2D est = alignSE2(from, to);
  EXPECT_NEAR(est.x, T.x, 1e-9);
  EXPECT_NEAR(est.y, T.y, 1e-9);
  EXPECT_NEAR(est.phi, T.phi, 1e-12);
  EXPECT_THROW(alignSE2({}, {}), std::invalid_argument);
  EXPECT_THROW(alignSE2(from, {from.begin(), from.end() - 1}), std::invalid_argument);
}

TEST(Ate, RigidlyTransformedCopyScoresZeroAfterAlignment) {
  const Trajectory gt = test::windingDrive(1500);
  const TPose2D T(6.2e5, 4.85e6, -2.2);  // a UTM-sized change of frame: needs double precision
  const AteResult r = computeAte(posesOf(gt), posesOf(test::transformed(gt, T)));
  EXPECT_LT(r.trans_m.rmse, 1e-6);
  EXPECT_LT(r.rot_deg.rmse, 1e-9);
  EXPECT_EQ(r.trans_m.count, gt.size());
  // The alignment is the inverse change of frame.
  const TPose2D inv = TPose2D(0, 0, 0) - T;
  EXPECT_NEAR(r.alignment.x, inv.x, 1e-4);
  EXPECT_NEAR(r.alignment.y, inv.y, 1e-4);
  EXPECT_NEAR(r.alignment.phi, inv.phi, 1e-12);
}

TEST(Ate, ScaledSquareHasTheHandComputedResidual) {
  // Corners of a 2x2 square against a 4x4 square: by symmetry the best rigid fit is the identity and
  // every corner is sqrt(2) m off.
  const std::vector<TPose2D> gt{{1, 1, 0}, {-1, 1, 0}, {-1, -1, 0}, {1, -1, 0}};
  const std::vector<TPose2D> est{{2, 2, 0}, {-2, 2, 0}, {-2, -2, 0}, {2, -2, 0}};
  const AteResult r = computeAte(gt, est);
  EXPECT_NEAR(r.trans_m.rmse, std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(r.trans_m.max, std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(r.alignment.phi, 0.0, 1e-12);
}

TEST(Rpe, KnownConstantPerFrameOffset) {
  // Each estimated step is the true step followed by a constant extra motion `off`: the error pose
  // inv(dGT) dEst is exactly `off` for every frame.
  const TPose2D off(0.1, 0.05, 0.01);
  const Trajectory gt = test::windingDrive(400);
  Trajectory est = gt;
  for (std::size_t k = 1; k < est.size(); ++k)
    est[k].pose = est[k - 1].pose + ((gt[k].pose - gt[k - 1].pose) + off);
  const RpeResult r = computeRpe(posesOf(gt), posesOf(est));
  ASSERT_EQ(r.per_frame_trans_m.size(), gt.size() - 1);
  const double t = std::hypot(off.x, off.y), deg = off.phi * 180.0 / std::numbers::pi;
  for (std::size_t i = 0; i < r.per_frame_trans_m.size(); ++i) {
    ASSERT_NEAR(r.per_frame_trans_m[i], t, 1e-9) << i;
    ASSERT_NEAR(r.per_frame_rot_deg[i], deg, 1e-9) << i;
  }
  EXPECT_NEAR(r.trans_m.rmse, t, 1e-9);
  EXPECT_NEAR(r.rot_deg.mean, deg, 1e-9);
  EXPECT_NEAR(r.trans_m.std, 0.0, 1e-9);
}

TEST(Rpe, AConstantWorldOffsetDoesNotChangeRelativeMotion) {
  const Trajectory gt = test::windingDrive(300);
  const RpeResult r = computeRpe(posesOf(gt), posesOf(test::transformed(gt, TPose2D(5, -3, 0.3))));
  EXPECT_LT(r.trans_m.max, 1e-9);
  EXPECT_LT(r.rot_deg.max, 1e-9);
}

TEST(ErrorStats, SummarisesAList) {
  const ErrorStats s = computeStats({3, 1, 4, 1, 5});
  EXPECT_EQ(s.count, 5u);
  EXPECT_DOUBLE_EQ(s.mean, 14.0 / 5);
  EXPECT_DOUBLE_EQ(s.median, 3.0);
  EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(52.0 / 5));
  EXPECT_DOUBLE_EQ(s.min, 1.0);
  EXPECT_DOUBLE_EQ(s.max, 5.0);
  EXPECT_DOUBLE_EQ(computeStats({1, 2, 3, 4}).median, 2.5);
  EXPECT_TRUE(std::isnan(computeStats({}).rmse));
}
