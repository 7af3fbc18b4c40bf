#pragma once
// The KITTI odometry metric as the radar-odometry literature reports it (KITTI devkit
// evaluate_odometry.cpp; pyboreas' radar benchmark): for every start frame (every `step_frames`
// frames) and every segment length L in 100, 200, ..., 800 m, the segment ends at the first frame
// whose ground-truth cumulative distance exceeds the start's by more than L; with the relative
// motions dGT = inv(P_gt_i) P_gt_j and dEst = inv(P_est_i) P_est_j, the error pose
// E = inv(dGT) dEst gives t_err = |trans(E)| / L and r_err = |angle(E)| / L. The result is the mean
// over all segments of all lengths (and, for plots, per length).
#include <mrpt/math/TPose2D.h>

#include <cstddef>
#include <vector>

namespace radarslam::eval {

struct KittiParams {
  std::vector<double> lengths_m{100, 200, 300, 400, 500, 600, 700, 800};  ///< valid (0, 1e5]
  /// Start a segment every `step_frames` frames. The devkit uses 10 at KITTI's 10 Hz (one start per
  /// second); spinning radars turn at 4 Hz, so 4 keeps one start per second (as pyboreas' radar
  /// benchmark does).
  unsigned step_frames = 4;  ///< valid [1, 1000000]
};

struct KittiSegment {
  std::size_t first = 0, last = 0;  ///< frame indices (into the associated poses)
  double length_m = 0;              ///< the nominal length L
  double t_err = 0;                 ///< |trans(E)| / L (a ratio; x100 for percent)
  double r_err_rad_per_m = 0;       ///< |angle(E)| / L
};

struct KittiLengthStats {
  double length_m = 0;
  std::size_t segments = 0;
  double t_err_percent = 0;       ///< NaN when segments == 0
  double r_err_deg_per_100m = 0;  ///< NaN when segments == 0
};

struct KittiResult {
  std::size_t segments = 0;
  double t_err_percent = 0;       ///< NaN when there is no segment (path shorter than the shortest L)
  double r_err_deg_per_m = 0;     ///< NaN when there is no segment
  double r_err_deg_per_100m = 0;  ///< NaN when there is no segment
  std::vector<KittiLengthStats> per_length;
  std::vector<KittiSegment> segment_errors;
  bool valid() const { return segments > 0; }
};

/// Cumulative ground-truth distance at each frame (metres, starts at 0).
std::vector<double> cumulativeDistances(const std::vector<mrpt::math::TPose2D>& poses);

/// `gt` and `est` are matched frame by frame (same size). Throws std::invalid_argument otherwise.
KittiResult computeKittiMetric(const std::vector<mrpt::math::TPose2D>& gt,
                               const std::vector<mrpt::math::TPose2D>& est, const KittiParams& params = {});

}  // namespace radarslam::eval
