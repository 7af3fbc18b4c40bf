#pragma once
// When the current frame becomes the new keyframe (paper Sec. III-A, following ORB-SLAM): too few
// matches with the keyframe, or moved / turned too far from it. The authors' configuration makes
// a keyframe every 2 m or 0.2 rad; our default is 1 m (see docs/odometry.md).
#include <mrpt/math/TPose2D.h>

namespace radarslam {

struct KeyframeParams {
  double max_translation_m = 1.0;  ///< authors: 2 m; 1 m keeps frame-to-frame tracking at road speeds
                                   ///< (docs/odometry.md); valid (0, 1000]
  double max_rotation_rad = 0.2;   ///< authors: 0.2 rad; valid (0, 6.2832]
  int min_inliers = 60;  ///< fewer inliers with the keyframe than this -> new keyframe; valid [0, 100000]
};

/// `motion` = T_keyframe_current; `inliers` = consistent matches with the keyframe.
bool needNewKeyframe(const KeyframeParams& params, const mrpt::math::TPose2D& motion, int inliers);

}  // namespace radarslam
