// Unit tests of the localisation module on a synthetic world (test/reloc/synthetic_world.h).
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "radarslam/core/errors.h"
#include "radarslam/core/yaml_params.h"
#include "radarslam/reloc/global_localizer.h"
#include "radarslam/reloc/localizer.h"
#include "radarslam/reloc/map_tracker.h"
#include "synthetic_world.h"

namespace radarslam {
namespace {

using test::SyntheticWorld;

double deg(double rad) { return std::abs(std::remainder(rad, 2 * M_PI)) * 180 / M_PI; }

class Reloc : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    world_ = new SyntheticWorld(SyntheticWorld::make(7));
    map_ = new KeyframeMap(world_->map());
  }
  static void TearDownTestSuite() {
    delete map_;
    delete world_;
  }
  static SyntheticWorld* world_;
  static KeyframeMap* map_;
};
SyntheticWorld* Reloc::world_ = nullptr;
KeyframeMap* Reloc::map_ = nullptr;

TEST_F(Reloc, GlobalFixOnRotatedTranslatedKeyframeView) {
  const GlobalLocalizer global(*map_);
  EXPECT_EQ(global.descriptorsComputed(), map_->keyframes.size());  // the map has none stored
  for (const mrpt::math::TPose2D truth :
       {mrpt::math::TPose2D{101.0, 1.3, 0.35}, mrpt::math::TPose2D{57.2, -0.8, -2.9},
        mrpt::math::TPose2D{230.5, 0.5, 1.2}}) {
    // Another noise and dropout draw than the map's keyframe clouds.
    const auto cloud = world_->scan(truth, 99);
    const GlobalFix fix = global.localize(cloud);
    ASSERT_TRUE(fix.found) << "at x = " << truth.x;
    EXPECT_LT(std::hypot(fix.pose.x - truth.x, fix.pose.y - truth.y), 0.3) << "at x = " << truth.x;
    EXPECT_LT(deg(fix.pose.phi - truth.phi), 1.0) << "at x = " << truth.x;
    EXPECT_LT(std::abs(map_->keyframes[fix.keyframe].pose.x - truth.x), 30.0);
  }
}

TEST_F(Reloc, TrackerFollowsSequenceAndCovarianceIsPositiveDefinite) {
  MapTracker tracker(*map_);
  // A drive in the other lane with a slow weave; the prediction is the previous estimate
  // composed with a noisy (biased) odometry increment.
  mrpt::math::TPose2D est{5.0, 2.0, 0.0};
  mrpt::math::TPose2D prev_truth = est;
  double max_err = 0, max_head = 0;
  int rebuilt = 0;
  for (int i = 1; i <= 100; ++i) {
    const double x = 5.0 + 2.3 * i;
    const mrpt::math::TPose2D truth{x, 2.0 + 0.8 * std::sin(x / 20), 0.04 * std::cos(x / 20)};
    const mrpt::poses::CPose2D motion = mrpt::poses::CPose2D(truth) - mrpt::poses::CPose2D(prev_truth);
    const mrpt::poses::CPose2D noisy(motion.x() * 1.05 + 0.1, motion.y() - 0.1, motion.phi() + 0.01);
    const mrpt::math::TPose2D predicted = (mrpt::poses::CPose2D(est) + noisy).asTPose();
    const TrackResult r = tracker.track(world_->scan(truth, 5000 + i), predicted);
    ASSERT_TRUE(r.accepted) << "scan " << i << ": " << r.reason;
    rebuilt += r.submap_rebuilt;
    est = r.icp.pose;
    prev_truth = truth;
    max_err = std::max(max_err, std::hypot(est.x - truth.x, est.y - truth.y));
    max_head = std::max(max_head, deg(est.phi - truth.phi));
    EXPECT_GT(r.icp.fit_score, 0.7);
    const Eigen::Matrix3d& c = r.icp.covariance;
    EXPECT_LT((c - c.transpose()).norm(), 1e-12);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(c);
    EXPECT_GT(es.eigenvalues().minCoeff(), 0.0) << "scan " << i;
    EXPECT_LT(std::sqrt(c(0, 0)), 0.5);
  }
  EXPECT_LT(max_err, 0.2);
  EXPECT_LT(max_head, 0.5);
  EXPECT_GE(rebuilt, 10);  // the submap follows the drive (230 m / 15 m)
}

TEST_F(Reloc, LossIsDetectedWhenTheScanIsFromElsewhere) {
  MapTracker tracker(*map_);
  const GlobalLocalizer global(*map_);
  const SyntheticWorld other = SyntheticWorld::make(12345);
  int false_tracks = 0, false_fixes = 0;
  for (int i = 0; i < 4; ++i) {
    const mrpt::math::TPose2D pose{20.0 + 60 * i, 0.5, 0.0};
    const auto cloud = other.scan(pose, 700 + i);
    false_tracks += tracker.track(cloud, pose).accepted;
    false_fixes += global.localize(cloud).found;
  }
  EXPECT_EQ(false_tracks, 0);
  EXPECT_EQ(false_fixes, 0);
  // Beyond the end of the map there is no keyframe to track against.
  const TrackResult r = tracker.track(world_->scan({380, 0, 0}, 1), {380, 0, 0});
  EXPECT_FALSE(r.accepted);
  // A prediction far off (a wrong relocalisation) is not accepted either: the ICP either fails or
  // converges to a pose too far from the prediction.
  const TrackResult off = tracker.track(world_->scan({100, 0, 0}, 2), {100, 0, 1.2});
  EXPECT_FALSE(off.accepted && std::hypot(off.icp.pose.x - 100, off.icp.pose.y) > 1.0);
}

// The map twisted by `twist` rad about (cx, 0) for the keyframes with |x - cx| <= half_m: a stretch
// whose keyframes agree with each other but not with the map around them (a loop correction
// concentrated between keyframes).
KeyframeMap twistedStretch(const KeyframeMap& map, double cx, double half_m, double twist) {
  KeyframeMap bent = map;
  const mrpt::poses::CPose2D about(cx, 0, 0), turn(0, 0, twist);
  for (Keyframe& k : bent.keyframes)
    if (std::abs(k.pose.x - cx) <= half_m)
      k.pose = (about + turn + (mrpt::poses::CPose2D(-cx, 0, 0) + mrpt::poses::CPose2D(k.pose))).asTPose();
  return bent;
}

TEST_F(Reloc, AMapThatDisagreesWithItselfIsSeenFromTheAnchorsOwnCloud) {
  // 50 m of the map (x 150..200) turned by 3 deg about its middle: the submap around x = 176
  // (radius 60 m) is mostly untwisted, and the registration from the true pose follows those
  // keyframes, so the pose relative to the nearest keyframe (what a client uses) is 3 deg off.
  // Check (i) registers the scan against the anchor keyframe's cloud as well (twisted): the two
  // differ far beyond that alignment's covariance, and it holds the right pose relative to the
  // anchor. The anchor's own cloud agrees with its neighbours (all twisted within 20 m).
  const double twist = 3 * M_PI / 180;
  const KeyframeMap bent = twistedStretch(*map_, 175, 25, twist);
  const mrpt::math::TPose2D truth{176.0, 1.0, 0.02};
  const auto cloud = world_->scan(truth, 4242);
  MapTracker tracker(bent);
  const TrackResult r = tracker.track(cloud, truth);
  ASSERT_GE(r.anchor, 0);
  EXPECT_TRUE(r.accepted) << r.reason;
  EXPECT_TRUE(r.map_inconsistent) << "chi2 " << r.anchor_chi2;
  EXPECT_GT(r.anchor_chi2, MapTrackerParams{}.rival_chi2);
  // Relative to the anchor keyframe: its true pose is the untwisted map's.
  const auto k = static_cast<std::size_t>(r.anchor);
  const mrpt::poses::CPose2D true_rel =
      mrpt::poses::CPose2D(truth) - mrpt::poses::CPose2D(map_->keyframes[k].pose);
  auto relErrors = [&](const mrpt::math::TPose2D& est) {
    const mrpt::poses::CPose2D rel = mrpt::poses::CPose2D(est) - mrpt::poses::CPose2D(bent.keyframes[k].pose);
    return std::make_pair(std::hypot(rel.x() - true_rel.x(), rel.y() - true_rel.y()),
                          deg(rel.phi() - true_rel.phi()));
  };
  const auto [submap_m, submap_deg] = relErrors(r.icp.pose);
  const auto [anchor_m, anchor_deg] = relErrors(r.anchor_alignment.pose);
  EXPECT_GT(submap_deg, 1.5) << "the submap's majority is untwisted";
  EXPECT_LT(anchor_m, 0.2);
  EXPECT_LT(anchor_deg, 0.3);
  (void)submap_m;

  // The untwisted map agrees with itself at the same place.
  MapTracker straight(*map_);
  const TrackResult s = straight.track(cloud, truth);
  EXPECT_TRUE(s.accepted) << s.reason;
  EXPECT_FALSE(s.map_inconsistent);
  EXPECT_GE(s.anchor_chi2, 0.0) << "evaluated";
  EXPECT_LT(s.anchor_chi2, MapTrackerParams{}.rival_chi2);

  EXPECT_FALSE(s.anchor_alignment_differs);
  EXPECT_GE(s.anchor_keyframe_chi2, 0.0) << "evaluated";
  EXPECT_LT(s.anchor_keyframe_chi2, MapTrackerParams{}.rival_chi2);
  EXPECT_TRUE(r.anchor_alignment_differs);
  EXPECT_LT(r.anchor_keyframe_chi2, MapTrackerParams{}.rival_chi2)
      << "inside the stretch its neighbours agree";
  EXPECT_GT(r.map_disagreement(2, 2), std::pow(2 * M_PI / 180, 2)) << "the twist, as a heading variance";

  // Off.
  MapTrackerParams off;
  off.anchor_path_m = 0;
  MapTracker unchecked(bent, off);
  const TrackResult u = unchecked.track(cloud, truth);
  EXPECT_FALSE(u.map_inconsistent);
  EXPECT_LT(u.anchor_chi2, 0.0) << "not evaluated";
}

TEST_F(Reloc, AKeyframeOutOfPlaceAmongItsNeighboursIsSeenFromItsOwnCloud) {
  // One keyframe stored 0.8 m and 2 deg away from where its cloud was seen (an odometry that
  // stalled for a scan while mapping): the scan's registration follows the many keyframes around
  // it, but relative to that keyframe (the nearest, the one a client relates the pose to) the pose
  // is 0.8 m / 2 deg off. Both tests see it: the keyframe's own cloud registered against its
  // neighbours, and the scan registered against that cloud alone, which gives the pose relative
  // to it.
  KeyframeMap moved = *map_;
  const std::size_t k = 60;  // at x = 120 m
  moved.keyframes[k].pose.y += 0.8;
  moved.keyframes[k].pose.phi += 2 * M_PI / 180;
  const mrpt::math::TPose2D truth{120.1, 0.3, 0.0};
  MapTracker tracker(moved);
  const TrackResult r = tracker.track(world_->scan(truth, 777), truth);
  ASSERT_EQ(r.anchor, static_cast<long>(k));
  EXPECT_TRUE(r.accepted) << r.reason;
  EXPECT_LT(std::hypot(r.icp.pose.x - truth.x, r.icp.pose.y - truth.y), 0.1) << "the neighbours decide";
  EXPECT_GT(r.anchor_keyframe_chi2, MapTrackerParams{}.rival_chi2);
  EXPECT_TRUE(r.anchor_alignment_differs);
  EXPECT_TRUE(r.map_inconsistent);
  const mrpt::poses::CPose2D rel =
      mrpt::poses::CPose2D(r.anchor_alignment.pose) - mrpt::poses::CPose2D(moved.keyframes[k].pose);
  const mrpt::poses::CPose2D true_rel =
      mrpt::poses::CPose2D(truth) - mrpt::poses::CPose2D(map_->keyframes[k].pose);
  EXPECT_LT(std::hypot(rel.x() - true_rel.x(), rel.y() - true_rel.y()), 0.15) << "relative to the keyframe";
  EXPECT_LT(deg(rel.phi() - true_rel.phi()), 0.3);
  EXPECT_GT(std::sqrt(r.map_disagreement(1, 1)), 0.8) << "the keyframe's offset, as a variance";
  // In place, it agrees.
  MapTracker straight(*map_);
  const TrackResult s = straight.track(world_->scan(truth, 777), truth);
  EXPECT_FALSE(s.map_inconsistent);
  EXPECT_LT(s.anchor_keyframe_chi2, MapTrackerParams{}.rival_chi2);
}

TEST(RelocCovariance, CorridorIsUncertainAlongTheWalls) {
  // Two long parallel walls: the position along them is unobservable, across them well known.
  std::vector<Eigen::Vector2d> pts;
  for (double x = -80; x <= 80; x += 0.2) {
    pts.emplace_back(x, 6.0);
    pts.emplace_back(x, -6.0);
  }
  const LocalSubmap submap = LocalSubmap::fromPoints(pts, 0.5);
  std::vector<RadarPoint> scan;
  for (double x = -50; x <= 50; x += 0.5)
    for (const double y : {6.0, -6.0}) {
      RadarPoint p;
      p.x = static_cast<float>(x);
      p.y = static_cast<float>(y + 0.03 * std::sin(7 * x));
      scan.push_back(p);
    }
  const IcpResult r = submap.registerScan(scan, {0.0, 0.3, 0.01}, {});
  EXPECT_LT(std::abs(r.pose.y), 0.05);
  EXPECT_LT(deg(r.pose.phi), 0.1);
  EXPECT_GT(r.covariance(0, 0), 100 * r.covariance(1, 1));
}

TEST(RelocCovariance, HeadingFloorAddsTheModelErrorVarianceOnlyToTheHeading) {
  // A scattered scene: every direction well constrained, so sigma^2 H^-1 alone is tiny.
  std::vector<Eigen::Vector2d> pts;
  for (int i = 0; i < 400; ++i) pts.emplace_back(40 * std::sin(1.3 * i), 40 * std::cos(0.7 * i + 0.2));
  const LocalSubmap submap = LocalSubmap::fromPoints(pts, 0.1);
  std::vector<RadarPoint> scan;
  for (const auto& q : pts) {
    RadarPoint p;
    p.x = static_cast<float>(q.x() + 0.02 * std::sin(5 * q.y()));
    p.y = static_cast<float>(q.y());
    scan.push_back(p);
  }
  IcpParams none;
  none.heading_sigma_floor_deg = 0;
  IcpParams floored;
  floored.heading_sigma_floor_deg = 0.25;
  const IcpResult a = submap.registerScan(scan, {0.1, -0.1, 0.005}, none);
  const IcpResult b = submap.registerScan(scan, {0.1, -0.1, 0.005}, floored);
  EXPECT_LT(std::sqrt(a.covariance(2, 2)) * 180 / M_PI, 0.05);  // the point model alone: overconfident
  const double floor_rad = 0.25 * M_PI / 180;
  EXPECT_NEAR(b.covariance(2, 2) - a.covariance(2, 2), floor_rad * floor_rad, 1e-12);
  EXPECT_NEAR(b.covariance(0, 0), a.covariance(0, 0), 1e-15);
  EXPECT_NEAR(b.covariance(0, 2), a.covariance(0, 2), 1e-15);
}

// A one-keyframe map at the origin holding `pts` (tracker tests on hand-made scenes).
KeyframeMap oneKeyframeMap(const std::vector<Eigen::Vector2d>& pts) {
  KeyframeMap m;
  Keyframe k;
  k.id = 0;
  for (const auto& q : pts) k.points.push_back({static_cast<float>(q.x()), static_cast<float>(q.y()), 1.f});
  m.keyframes.push_back(std::move(k));
  return m;
}

std::vector<RadarPoint> scanOf(const std::vector<Eigen::Vector2d>& pts, double from_x, double to_x) {
  std::vector<RadarPoint> scan;
  for (const auto& q : pts)
    if (q.x() >= from_x && q.x() <= to_x) {
      RadarPoint p;
      p.x = static_cast<float>(q.x());
      p.y = static_cast<float>(q.y() + 0.02 * std::sin(7 * q.x()));
      scan.push_back(p);
    }
  return scan;
}

// Walls on both sides of a street and a post every `period_m`: the posts fix the position along
// the street only to within a period.
std::vector<Eigen::Vector2d> streetWithPosts(double period_m) {
  std::vector<Eigen::Vector2d> pts;
  for (double x = -80; x <= 80; x += 0.2) {
    pts.emplace_back(x, 6.0);
    pts.emplace_back(x, -6.0);
  }
  for (double x = -80; x <= 80; x += period_m)
    for (double d = -0.2; d <= 0.21; d += 0.2) pts.emplace_back(x + d, 3.0), pts.emplace_back(x, 3.0 + d);
  return pts;
}

// The tracker seeing the whole hand-made street (one keyframe, no copies).
MapTrackerParams wholeStreetParams() {
  MapTrackerParams params;
  params.submap.radius_m = 200;
  params.submap.max_path_m = 0;
  return params;
}

TEST(RelocTracker, AStreetThatRepeatsEveryFewMetresIsDegenerateAlongIt) {
  // Walls with posts every 2 m (a fence, parked cars in a row): the posts constrain the position
  // along the street locally (sigma^2 H^-1 is small and round: the eigenvalue ratio test passes),
  // but the scan fits as well 2 m further on. The fit profile makes it `degenerate` (fused with
  // the prediction by the localiser), with the shift's variance along the street.
  const std::vector<Eigen::Vector2d> pts = streetWithPosts(2.0);
  const KeyframeMap map = oneKeyframeMap(pts);
  MapTrackerParams params = wholeStreetParams();
  MapTracker tracker(map, params);
  const TrackResult r = tracker.track(scanOf(pts, -50, 50), {0.3, 0.2, 0.005});
  ASSERT_TRUE(r.icp.converged);
  EXPECT_LT(std::hypot(r.icp.pose.x, r.icp.pose.y), 0.1);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> icp_only(
      r.icp.covariance.topLeftCorner<2, 2>() - 4.0 * r.icp.weak_direction * r.icp.weak_direction.transpose());
  EXPECT_LT(icp_only.eigenvalues()(1), 100 * icp_only.eigenvalues()(0)) << "the eigenvalue test would pass";
  EXPECT_GT(r.icp.profile_fit, 0.97 * r.icp.fit_score);
  EXPECT_LE(r.icp.profile_chi2, params.rival_chi2) << "the scan cannot tell the next post from its own";
  EXPECT_FALSE(r.accepted);
  EXPECT_TRUE(r.degenerate) << r.reason;
  EXPECT_GT(std::abs(r.icp.weak_direction.x()), 0.9) << "along the street";
  EXPECT_GT(r.icp.covariance(0, 0), 4.0);

  // Off: accepted as well constrained.
  params.icp.profile_shift_m = 0;
  MapTracker trusting(map, params);
  const TrackResult t = trusting.track(scanOf(pts, -50, 50), {0.3, 0.2, 0.005});
  EXPECT_TRUE(t.accepted) << t.reason;

  // Whichever test makes the scan degenerate first (here the position sigma test, made strict),
  // the flat direction still gets the shift's variance.
  params.icp.profile_shift_m = MapTrackerParams{}.icp.profile_shift_m;
  params.max_position_sigma_m = 1e-3;
  MapTracker strict(map, params);
  const TrackResult s = strict.track(scanOf(pts, -50, 50), {0.3, 0.2, 0.005});
  EXPECT_TRUE(s.degenerate) << s.reason;
  EXPECT_NE(s.reason.find("flat along its weakest direction"), std::string::npos) << s.reason;
  EXPECT_GT(s.icp.covariance(0, 0), 4.0);
}

// 600 points scattered over 80 x 80 m: one alignment only.
std::vector<Eigen::Vector2d> scatteredScene() {
  std::vector<Eigen::Vector2d> pts;
  for (int i = 0; i < 600; ++i) pts.emplace_back(40 * std::sin(1.3 * i), 40 * std::cos(0.7 * i + 0.2));
  return pts;
}

TEST(RelocTracker, AScatteredSceneHasASteepFitProfile) {
  const std::vector<Eigen::Vector2d> pts = scatteredScene();
  const KeyframeMap map = oneKeyframeMap(pts);
  MapTracker tracker(map, wholeStreetParams());
  const TrackResult r = tracker.track(scanOf(pts, -100, 100), {0.2, -0.1, 0.005});
  EXPECT_TRUE(r.accepted) << r.reason;
  EXPECT_LT(r.icp.profile_fit, 0.5 * r.icp.fit_score);
  EXPECT_GT(r.icp.profile_chi2, 10 * MapTrackerParams{}.rival_chi2);
}

// Two rows of cars parked side by side (4.5 x 1.8 m outlines, a 2.5 m bay) either side of an aisle.
std::vector<Eigen::Vector2d> carParkRows() {
  std::vector<Eigen::Vector2d> pts;
  for (double x0 = -80; x0 <= 80; x0 += 2.5)
    for (const double y0 : {3.0, -7.5}) {
      for (double t = 0; t <= 1.8; t += 0.2) pts.emplace_back(x0 + t, y0), pts.emplace_back(x0 + t, y0 + 4.5);
      for (double t = 0.2; t < 4.5; t += 0.2)
        pts.emplace_back(x0, y0 + t), pts.emplace_back(x0 + 1.8, y0 + t);
    }
  return pts;
}

TEST(RelocTracker, ARowOfParkedCarsIsNotFlatWhereItsResidualsTellTheBaysApart) {
  // 2 m along the rows nearly every point still lies within the 1 m inlier gate of a car (a fit
  // ratio calls that flat), but the car sides are 0.2 - 0.5 m off: the robust cost tells the
  // shifted alignment from the solution far beyond the chi^2 bound, so the scan is tracked.
  const std::vector<Eigen::Vector2d> pts = carParkRows();
  const KeyframeMap map = oneKeyframeMap(pts);
  MapTracker tracker(map, wholeStreetParams());
  const TrackResult r = tracker.track(scanOf(pts, -50, 50), {0.3, 0.2, 0.005});
  ASSERT_TRUE(r.icp.converged);
  EXPECT_LT(std::hypot(r.icp.pose.x, r.icp.pose.y), 0.1);
  EXPECT_GT(r.icp.profile_fit, 0.975 * r.icp.fit_score) << "the bays are within the gate of each other";
  EXPECT_GT(r.icp.profile_chi2, MapTrackerParams{}.rival_chi2);
  EXPECT_TRUE(r.accepted) << r.reason;
}

TEST(RelocTracker, TheFitProfileOfAFeaturelessWallIsFlat) {
  // One straight wall: shifted along itself the scan fits exactly as well.
  std::vector<Eigen::Vector2d> pts;
  for (double x = -80; x <= 80; x += 0.2) pts.emplace_back(x, 6.0);
  const KeyframeMap map = oneKeyframeMap(pts);
  MapTracker tracker(map, wholeStreetParams());
  const TrackResult r = tracker.track(scanOf(pts, -50, 50), {0.3, 0.2, 0.005});
  EXPECT_LT(r.icp.profile_chi2, 1.0);
  EXPECT_GT(std::abs(r.icp.weak_direction.x()), 0.99) << "along the wall";
  EXPECT_FALSE(r.accepted);
  EXPECT_TRUE(r.degenerate) << r.reason;
}

// Check (h) found another alignment within a wide prediction: not trusted, fused as degenerate.
void expectAmbiguousReacquisition(const TrackResult& r) {
  EXPECT_TRUE(r.reacquisition);
  EXPECT_TRUE(r.reacquisition_ambiguous);
  EXPECT_FALSE(r.accepted);
  EXPECT_TRUE(r.degenerate) << r.reason;
}

// Registers the street's scan from `predicted`, a prediction known to +-6 m (3 sigma) along the
// street (check (h) re-acquires).
TrackResult trackWideAlongTheStreet(const std::vector<Eigen::Vector2d>& pts, const MapTrackerParams& params,
                                    const mrpt::math::TPose2D& predicted) {
  const KeyframeMap map = oneKeyframeMap(pts);
  MapTracker tracker(map, params);
  const Eigen::Matrix3d wide = Eigen::Vector3d(4.0, 0.01, 1e-4).asDiagonal();
  return tracker.track(scanOf(pts, -50, 50), predicted, -1, &wide);
}

TEST(RelocTracker, AWidePredictionIsAReacquisitionThatTestsTheOtherAlignments) {
  // After a degraded stretch the prediction is known to +-6 m (3 sigma) along the street. The
  // registration from it lands on the look-alike post 4 m on; the fit profile (2 m) does not see
  // it (the posts lose their match halfway between). Check (h) registers from further starts
  // within the prediction, finds alignments 4 m apart fitting as well: degenerate, with their
  // spread in the covariance.
  const std::vector<Eigen::Vector2d> pts = streetWithPosts(4.0);
  const KeyframeMap map = oneKeyframeMap(pts);
  MapTrackerParams params = wholeStreetParams();
  const mrpt::math::TPose2D predicted{3.6, 0.1, 0.0};
  const Eigen::Matrix3d wide = Eigen::Vector3d(4.0, 0.01, 1e-4).asDiagonal();
  {
    const TrackResult r = trackWideAlongTheStreet(pts, params, predicted);
    expectAmbiguousReacquisition(r);
    EXPECT_GT(r.icp.covariance(0, 0), 4.0) << "the alignments' spread along the street";
    EXPECT_LT(r.icp.covariance(1, 1), 0.1) << "across it the walls still fix the position";
  }
  {  // without the prediction's covariance: trusted 4 m off
    MapTracker tracker(map, params);
    const TrackResult r = tracker.track(scanOf(pts, -50, 50), predicted);
    EXPECT_FALSE(r.reacquisition);
    EXPECT_TRUE(r.accepted) << r.reason;
    EXPECT_NEAR(r.icp.pose.x, 4.0, 0.1);
  }
  {  // off
    params.reacquisition_starts = 0;
    MapTracker tracker(map, params);
    EXPECT_TRUE(tracker.track(scanOf(pts, -50, 50), predicted, -1, &wide).accepted);
  }
}

TEST(RelocTracker, AnotherAlignmentIsARivalOnlyWhenTheScanCannotTellItFromTheBest) {
  // The street with a post every 4 m, and two fences across it near x = 12 m: 4 m along the street
  // the posts and walls fit as well, the fences (a few percent of the scan) do not. The fit score of
  // that alignment is ~0.95 of the best's, "almost as well" by any fixed ratio; its robust cost is
  // higher by far more than the chi^2(3) bound in the registration's own units, so the scan tells
  // the two apart: the one alignment is kept, unique, and trusted.
  std::vector<Eigen::Vector2d> pts = streetWithPosts(4.0);
  for (double y = -5; y <= 3; y += 0.2) pts.emplace_back(12.0, y), pts.emplace_back(13.5, y);
  MapTrackerParams params = wholeStreetParams();
  const mrpt::math::TPose2D predicted{2.8, 0.1, 0.0};
  {
    const TrackResult r = trackWideAlongTheStreet(pts, params, predicted);
    EXPECT_TRUE(r.reacquisition);
    EXPECT_FALSE(r.reacquisition_ambiguous);
    EXPECT_TRUE(r.accepted) << r.reason;
    EXPECT_LT(std::hypot(r.icp.pose.x, r.icp.pose.y), 0.1) << "the fences' alignment is kept";
  }
  {  // Every other alignment counted as a rival: the look-alike 4 m on makes it ambiguous.
    params.rival_chi2 = 1e12;
    const TrackResult r = trackWideAlongTheStreet(pts, params, predicted);
    expectAmbiguousReacquisition(r);
    EXPECT_LT(std::hypot(r.icp.pose.x, r.icp.pose.y), 0.1);
    EXPECT_GT(r.icp.covariance(0, 0), 4.0 / 2 * 0.9) << "the look-alike's spread";
  }
}

TEST(RelocTracker, AWideHeadingPredictionTestsTheOtherHeadings) {
  // A round place: a circular wall 30 m away and a post every 10 deg at 20 m. Turned by 10 deg it
  // looks the same. The prediction's heading is 9 deg off and known to +-15 deg (3 sigma, beyond
  // the ICP's heading capture range of 3 m at the submap radius): from it the registration lands
  // on the look-alike 10 deg away, and the xy fit profile does not see it. Heading starts find the
  // true alignment as a rival: degenerate, with the spread in the heading variance.
  std::vector<Eigen::Vector2d> pts;
  for (double a = 0; a < 2 * M_PI; a += 0.01) pts.emplace_back(30 * std::cos(a), 30 * std::sin(a));
  for (int k = 0; k < 36; ++k) {
    const double a = k * 10 * M_PI / 180;
    for (double d = -0.2; d <= 0.21; d += 0.2)
      pts.emplace_back(20 * std::cos(a) + d, 20 * std::sin(a)),
          pts.emplace_back(20 * std::cos(a), 20 * std::sin(a) + d);
  }
  const KeyframeMap map = oneKeyframeMap(pts);
  MapTrackerParams params;  // submap radius 60 m: heading capture 3 m / 60 m = 2.9 deg
  params.submap.max_path_m = 0;
  const mrpt::math::TPose2D predicted{0.0, 0.0, 9 * M_PI / 180};
  const double sigma_phi = 5 * M_PI / 180;
  const Eigen::Matrix3d wide = Eigen::Vector3d(0.01, 0.01, sigma_phi * sigma_phi).asDiagonal();
  MapTracker tracker(map, params);
  const TrackResult r = tracker.track(scanOf(pts, -100, 100), predicted, -1, &wide);
  expectAmbiguousReacquisition(r);
  EXPECT_GT(r.icp.covariance(2, 2), 0.5 * std::pow(10 * M_PI / 180, 2) * 0.9) << "the rivals' heading spread";
  // A narrow heading prediction at the same place is ordinary tracking, trusted 10 deg off.
  const Eigen::Matrix3d narrow = Eigen::Vector3d(0.01, 0.01, 1e-5).asDiagonal();
  const TrackResult t = tracker.track(scanOf(pts, -100, 100), predicted, -1, &narrow);
  EXPECT_FALSE(t.reacquisition);
  EXPECT_TRUE(t.accepted) << t.reason;
  EXPECT_NEAR(std::abs(t.icp.pose.phi) * 180 / M_PI, 10, 0.5);
}

TEST(RelocTracker, AReacquisitionInADistinctSceneFindsTheOneAlignment) {
  const std::vector<Eigen::Vector2d> pts = scatteredScene();
  const KeyframeMap map = oneKeyframeMap(pts);
  MapTracker tracker(map, wholeStreetParams());
  const Eigen::Matrix3d wide = Eigen::Vector3d(2.0, 1.0, 1e-4).asDiagonal();
  const TrackResult r = tracker.track(scanOf(pts, -100, 100), {0.8, -0.4, 0.005}, -1, &wide);
  EXPECT_TRUE(r.reacquisition);
  EXPECT_FALSE(r.reacquisition_ambiguous);
  EXPECT_TRUE(r.accepted) << r.reason;
  EXPECT_LT(std::hypot(r.icp.pose.x, r.icp.pose.y), 0.1);
  // A narrow prediction is ordinary tracking.
  const Eigen::Matrix3d narrow = Eigen::Vector3d(0.01, 0.01, 1e-5).asDiagonal();
  EXPECT_FALSE(tracker.track(scanOf(pts, -100, 100), {0.2, -0.1, 0.005}, -1, &narrow).reacquisition);
}

TEST(RelocParams, LoadFromYamlAndRejectUnknownKeys) {
  const YamlParams yaml = YamlParams::fromText(
      "localization:\n  max_missed_scans: 5\n  global:\n    candidates: 9\n    m2dp:\n      rings: 6\n"
      "  tracker:\n    min_fit_score: 0.5\n    icp:\n      cauchy_m: 0.7\n    submap:\n      radius_m: 80\n");
  LocalizerParams p;
  loadParams(yaml.section("localization"), p);
  EXPECT_NO_THROW(yaml.rejectUnknownKeys());
  EXPECT_EQ(p.max_missed_scans, 5);
  EXPECT_EQ(p.global.candidates, 9u);
  EXPECT_EQ(p.global.m2dp.rings, 6);
  EXPECT_DOUBLE_EQ(p.tracker.min_fit_score, 0.5);
  EXPECT_DOUBLE_EQ(p.tracker.icp.cauchy_m, 0.7);
  EXPECT_DOUBLE_EQ(p.tracker.submap.radius_m, 80);
  // Contested places are followed after a loss only when switched on (off by default).
  EXPECT_FALSE(p.resolve_contested_fixes_after_loss);
  EXPECT_FALSE(p.resolve_contested_fixes);
  const YamlParams after_loss =
      YamlParams::fromText("localization:\n  resolve_contested_fixes_after_loss: true\n");
  loadParams(after_loss.section("localization"), p);
  EXPECT_NO_THROW(after_loss.rejectUnknownKeys());
  EXPECT_TRUE(p.resolve_contested_fixes_after_loss);
  const YamlParams typo = YamlParams::fromText("localization:\n  tracker:\n    min_fit_scor: 0.5\n");
  LocalizerParams q;
  loadParams(typo.section("localization"), q);
  EXPECT_THROW(typo.rejectUnknownKeys(), InputError);
  const YamlParams bad = YamlParams::fromText("localization:\n  tracker:\n    min_fit_score: 2\n");
  EXPECT_THROW(loadParams(bad.section("localization"), q), InputError);
  const YamlParams starts = YamlParams::fromText("localization:\n  tracker:\n    reacquisition_starts: 11\n");
  EXPECT_THROW(loadParams(starts.section("localization"), q), InputError);
}

}  // namespace
}  // namespace radarslam
