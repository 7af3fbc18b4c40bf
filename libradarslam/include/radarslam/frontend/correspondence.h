#pragma once
// A matched pair of 2-D points: `cur` in the current frame, `ref` in the reference (key)frame,
// both in metres. Poses relating them are T_ref_cur: ref = T_ref_cur (+) cur.
#include <Eigen/Core>

#include <vector>

namespace radarslam {

struct Correspondence {
  Eigen::Vector2d cur = Eigen::Vector2d::Zero();
  Eigen::Vector2d ref = Eigen::Vector2d::Zero();
  double weight = 1.0;
  double descriptor_distance = 0.0;
  int cur_index = -1;  ///< keypoint index in the current frame
  int ref_index = -1;  ///< keypoint index in the reference frame
};

using Correspondences = std::vector<Correspondence>;

}  // namespace radarslam
