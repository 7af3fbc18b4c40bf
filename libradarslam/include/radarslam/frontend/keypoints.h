#pragma once
// Keypoints and descriptors on the Cartesian radar image (paper Sec. III-A; the paper used SURF,
// which OpenCV here does not have). The detector/descriptor is chosen by name; see
// docs/odometry.md for the measurements behind the default.
#include <opencv2/core/mat.hpp>
#include <opencv2/core/types.hpp>

#include <memory>
#include <string>
#include <vector>

namespace radarslam {

struct KeypointParams {
  std::string detector = "orb";  ///< orb | akaze | brisk | fast_orb
  int max_keypoints = 1000;      ///< strongest kept (orb, fast_orb); valid [10, 100000]
  int fast_threshold = 12;       ///< FAST threshold (orb, fast_orb, brisk); valid [1, 255]
  int pyramid_levels = 1;        ///< ORB pyramid levels (radar images have no scale change); valid [1, 16]
  int patch_size = 31;           ///< ORB descriptor patch (px); valid [5, 127]
  double blur_sigma_px =
      0.0;               ///< Gaussian pre-smoothing of the image before detection (0 = off); valid [0, 20]
  bool subpixel = true;  ///< refine locations to sub-pixel on the smoothed image
};

struct ImageKeypoints {
  std::vector<cv::KeyPoint> points;  ///< pixel positions (col, row), sub-pixel when refined
  cv::Mat descriptors;               ///< one row per point
  int norm_type = 0;                 ///< cv::NORM_HAMMING or cv::NORM_L2
};

class KeypointExtractor {
 public:
  explicit KeypointExtractor(const KeypointParams& params = {});
  ~KeypointExtractor();
  KeypointExtractor(KeypointExtractor&&) noexcept;
  KeypointExtractor& operator=(KeypointExtractor&&) noexcept;

  /// Detect then describe. `mask` (optional, CV_8UC1) excludes pixels where it is 0.
  ImageKeypoints extract(const cv::Mat& image, const cv::Mat& mask = {}) const;
  /// The two stages separately (for benchmarks).
  std::vector<cv::KeyPoint> detect(const cv::Mat& image, const cv::Mat& mask = {}) const;
  ImageKeypoints describe(const cv::Mat& image, std::vector<cv::KeyPoint> points) const;

  const KeypointParams& params() const { return params_; }

 private:
  KeypointParams params_;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace radarslam
