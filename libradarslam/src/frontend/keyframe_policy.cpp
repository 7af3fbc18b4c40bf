#include "radarslam/frontend/keyframe_policy.h"

#include <cmath>

namespace radarslam {

bool needNewKeyframe(const KeyframeParams& params, const mrpt::math::TPose2D& motion, int inliers) {
  return inliers < params.min_inliers || std::hypot(motion.x, motion.y) >= params.max_translation_m ||
         std::abs(motion.phi) >= params.max_rotation_rad;
}

}  // namespace radarslam
