// Local mapping's data association (paper Sec. III-B): the observations local BA adjusts are the
// tracker's measurements (patch-aligned positions, OdometryStep::keyframe_observations), not the
// detector's own position of the same landmark in the new keyframe, and a map point's later
// observations are shifted so that all of them locate the same patch.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "local_mapper.h"
#include "radarslam/slam/slam_params.h"

namespace radarslam::slam_detail {
namespace {

using mrpt::math::TPose2D;

Eigen::Vector2d toLocal(const TPose2D& p, const Eigen::Vector2d& w) {
  const double c = std::cos(p.phi), s = std::sin(p.phi), dx = w.x() - p.x, dy = w.y() - p.y;
  return {c * dx + s * dy, -s * dx + c * dy};
}
Eigen::Vector2d toWorld(const TPose2D& p, const Eigen::Vector2d& l) {
  const double c = std::cos(p.phi), s = std::sin(p.phi);
  return {p.x + c * l.x() - s * l.y(), p.y + s * l.x() + c * l.y()};
}

/// A blank 400 x 200 scan (the peak cloud and descriptor are not what this test is about).
std::shared_ptr<CObservationRadarScan> blankScan(int index) {
  auto scan = std::make_shared<CObservationRadarScan>();
  scan->resize(400, 200);
  scan->range_resolution_m = 0.0438;
  for (std::uint32_t a = 0; a < 400; ++a)
    scan->azimuth_stamps_ns[a] = 1'600'000'000'000'000'000LL + index * 250'000'000LL + a * 625'000LL;
  scan->updateReferenceTime();
  return scan;
}

KeyframeJob job(std::uint64_t id, const TPose2D& pose, std::vector<Eigen::Vector2d> keypoints,
                std::vector<KeyframeObservation> observations) {
  KeyframeJob j;
  j.id = id;
  j.stamp = static_cast<StampNs>(id) * 250'000'000LL;
  j.odom_pose = pose;
  j.keypoints = std::move(keypoints);
  j.observations = std::move(observations);
  j.scan = blankScan(static_cast<int>(id));
  return j;
}

// Landmark L; each keyframe's detector puts it somewhere else (jitter), the tracker measures where
// the previous keyframe's keypoint patch lies. Every observation of L's map point, taken through
// the keyframe's true pose, must land on the first keyframe's keypoint (the point's first patch).
TEST(LocalMapperAssociation, ObservationsAreTheTrackersMeasurementsOfOnePatch) {
  SlamParams params;
  params.local_mapping.bundle_adjustment = false;  // association only
  SlamState state;
  LocalMapper mapper(state, params);
  const Eigen::Vector2d L(10, 5), M(-8, 12);
  const TPose2D p0{0, 0, 0}, p1{2, 0.1, 0.05}, p2{4, 0.5, 0.35};
  // Detector positions: exact in keyframe 0, off by 0.3 m / 0.25 m in keyframes 1 and 2.
  const Eigen::Vector2d d1 = toLocal(p1, L) + Eigen::Vector2d(0.3, 0),
                        d2 = toLocal(p2, L) + Eigen::Vector2d(-0.2, 0.25);
  mapper.insert(job(0, p0, {toLocal(p0, L), toLocal(p0, M)}, {}));
  // Keyframe 1: keyframe 0's L patch measured exactly (and linked to the detector's keypoint 0);
  // M's patch measured too, with no keypoint of keyframe 1 there.
  mapper.insert(job(1, p1, {d1}, {{0, 0, toLocal(p1, L)}, {1, -1, toLocal(p1, M)}}));
  // Keyframe 2: keyframe 1's keypoint patch (the detector's d1: physically 0.3 m off L) measured.
  mapper.insert(job(2, p2, {d2}, {{0, 0, toLocal(p2, toWorld(p1, d1))}}));

  ASSERT_EQ(state.points.size(), 2u);
  const TPose2D poses[] = {p0, p1, p2};
  const SlamMapPoint& l = state.points[0];
  ASSERT_EQ(l.observations.size(), 3u);
  for (const auto& o : l.observations) {
    const Eigen::Vector2d w = toWorld(poses[o.keyframe], o.z);
    EXPECT_NEAR(w.x(), L.x(), 1e-9) << "keyframe " << o.keyframe;
    EXPECT_NEAR(w.y(), L.y(), 1e-9) << "keyframe " << o.keyframe;
  }
  const SlamMapPoint& m = state.points[1];
  ASSERT_EQ(m.observations.size(), 2u);  // no keypoint in keyframe 1: the chain ends there
  for (const auto& o : m.observations) EXPECT_NEAR((toWorld(poses[o.keyframe], o.z) - M).norm(), 0, 1e-9);
}

// Hostile indices from a tracker bug must not corrupt the state: out-of-range observations are
// ignored, and one keypoint never joins two map points.
TEST(LocalMapperAssociation, OutOfRangeAndDuplicateObservationsAreIgnored) {
  SlamParams params;
  params.local_mapping.bundle_adjustment = false;
  SlamState state;
  LocalMapper mapper(state, params);
  mapper.insert(job(0, {0, 0, 0}, {{5, 0}, {0, 5}}, {}));
  mapper.insert(job(1, {1, 0, 0}, {{4, 0}},
                    {{7, 0, {4, 0}}, {-1, 0, {4, 0}}, {0, 3, {4, 0}}, {0, 0, {4, 0}}, {1, 0, {-1, 5}}}));
  ASSERT_EQ(state.points.size(), 1u);
  EXPECT_EQ(state.points[0].observations.size(), 2u);
}

}  // namespace
}  // namespace radarslam::slam_detail
