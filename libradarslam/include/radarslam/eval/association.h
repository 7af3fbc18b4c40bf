#pragma once
// Pairs an estimated trajectory with ground truth: the ground truth is interpolated at every
// estimate stamp (core/trajectory.h interpolatePose). Estimates outside the ground truth's time
// span, or inside a gap between ground-truth samples wider than max_gt_gap, are dropped and counted.
#include <mrpt/math/TPose2D.h>

#include <cstddef>
#include <vector>

#include "radarslam/core/trajectory.h"

namespace radarslam::eval {

struct Association {
  std::vector<StampNs> stamps;           ///< the kept estimate stamps
  std::vector<mrpt::math::TPose2D> est;  ///< estimated poses at `stamps`
  std::vector<mrpt::math::TPose2D> gt;   ///< ground truth interpolated at `stamps`
  std::size_t dropped_before_gt = 0;     ///< estimates stamped before the first ground-truth pose
  std::size_t dropped_after_gt = 0;      ///< ... after the last one
  std::size_t dropped_in_gt_gaps = 0;    ///< ... between two ground-truth poses > max_gt_gap apart
  std::size_t size() const { return stamps.size(); }
  std::size_t dropped() const { return dropped_before_gt + dropped_after_gt + dropped_in_gt_gaps; }
};

/// Both trajectories must have strictly increasing stamps (checked by evaluate()).
Association associate(const Trajectory& est, const Trajectory& gt, StampNs max_gt_gap_ns);

}  // namespace radarslam::eval
