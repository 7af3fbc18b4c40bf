#include "radarslam/frontend/structure_information.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <cmath>

namespace radarslam {

Eigen::Matrix2d structureInformation(const cv::Mat& smooth, cv::Point2f pixel, int radius_px,
                                     const Eigen::Matrix2d& pixel_to_metres,
                                     const Eigen::Vector2d& position_m,
                                     const StructureInformationParams& params) {
  const Eigen::Matrix2d identity = Eigen::Matrix2d::Identity();
  const int cx = cvRound(pixel.x), cy = cvRound(pixel.y), r = radius_px;
  if (!params.enabled || smooth.type() != CV_32F || r < 1 || cx - r - 1 < 0 || cy - r - 1 < 0 ||
      cx + r + 1 >= smooth.cols || cy + r + 1 >= smooth.rows)
    return identity;
  Eigen::Matrix2d s = Eigen::Matrix2d::Zero();  // in pixel coordinates
  for (int y = cy - r; y <= cy + r; ++y) {
    const float* row = smooth.ptr<float>(y);
    const float* up = smooth.ptr<float>(y - 1);
    const float* down = smooth.ptr<float>(y + 1);
    for (int x = cx - r; x <= cx + r; ++x) {
      const Eigen::Vector2d g(0.5 * (row[x + 1] - row[x - 1]), 0.5 * (down[x] - up[x]));
      s += g * g.transpose();
    }
  }
  // Gradients transform with the inverse transpose of the pixel-to-metres map.
  const Eigen::Matrix2d a = pixel_to_metres.inverse().transpose();
  const Eigen::Matrix2d s_m = a * s * a.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(s_m);
  const double largest = eig.eigenvalues()(1);
  if (!(largest > 0) || !s_m.allFinite()) return identity;
  const double range = position_m.norm();
  if (range > 0) {
    const Eigen::Vector2d normal = eig.eigenvectors().col(1);  // across the structure
    const double cos_to_radial = std::abs(normal.dot(position_m / range));
    if (cos_to_radial >= std::cos(params.beam_blur_tolerance_deg * M_PI / 180.0)) return identity;
  }
  return s_m / largest;
}

}  // namespace radarslam
