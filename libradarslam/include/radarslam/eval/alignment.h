#pragma once
// Closed-form rigid SE(2) alignment of two matched point sets (Horn 1987 / Umeyama 1991 without
// scale), in double precision. mrpt::tfest::se2_l2 solves the same problem but stores the points
// as float (TMatchingPairList), which loses centimetres on UTM-sized coordinates.
#include <mrpt/math/TPoint2D.h>
#include <mrpt/math/TPose2D.h>

#include <vector>

namespace radarslam::eval {

/// The transform T minimising sum_i |T (+) from_i - to_i|^2 (T maps `from` onto `to`).
/// Requires from.size() == to.size() >= 1 (one point gives the translation only); throws
/// std::invalid_argument otherwise.
mrpt::math::TPose2D alignSE2(const std::vector<mrpt::math::TPoint2D>& from,
                             const std::vector<mrpt::math::TPoint2D>& to);

}  // namespace radarslam::eval
