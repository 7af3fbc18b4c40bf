#pragma once
// Closed-form least-squares SE(2) from matched points (paper Sec. III-A, "SVD" [Challis 1995]),
// computed with MRPT's mrpt::tfest::se2_l2.
#include <mrpt/math/TPose2D.h>

#include <optional>

#include "radarslam/frontend/correspondence.h"

namespace radarslam {

/// T_ref_cur minimising sum |ref - T (+) cur|^2; nullopt with fewer than 2 correspondences.
std::optional<mrpt::math::TPose2D> fitPoseSvd(const Correspondences& matches);

}  // namespace radarslam
