#pragma once
// Pose-graph optimisation (paper Sec. III-D) of the shared state: every keyframe a node, an
// odometry edge between consecutive keyframes (information from OdometryEdgeParams), every active
// accepted loop an edge; optimised with backend/pose_graph.h (Ceres LM + chi^2 loop rejection).
// Then the map update: keyframes get the optimised poses, map points move with their reference
// keyframe, keyframes inserted while the optimisation ran follow their predecessor.
#include "slam_state.h"

namespace radarslam::slam_detail {

/// Information (x, y, phi) of an odometry edge of length `distance_m`.
Eigen::Matrix3d odometryInformation(const OdometryEdgeParams& params, double distance_m, bool lost);

/// Optimises and applies the correction. Returns false if there was nothing to optimise.
bool optimiseAndCorrect(SlamState& state, const SlamParams& params);

}  // namespace radarslam::slam_detail
