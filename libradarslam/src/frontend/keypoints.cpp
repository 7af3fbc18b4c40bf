#include "radarslam/frontend/keypoints.h"

#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>

#include "radarslam/core/errors.h"

namespace radarslam {

struct KeypointExtractor::Impl {
  cv::Ptr<cv::Feature2D> detector;
  cv::Ptr<cv::Feature2D> descriptor;
  int norm_type = cv::NORM_HAMMING;
};

KeypointExtractor::KeypointExtractor(const KeypointParams& params)
    : params_(params), impl_(std::make_unique<Impl>()) {
  const auto& p = params_;
  auto orb = [&] {
    return cv::ORB::create(p.max_keypoints, 1.2f, std::max(1, p.pyramid_levels), p.patch_size, 0, 2,
                           cv::ORB::FAST_SCORE, p.patch_size, p.fast_threshold);
  };
  if (p.detector == "orb") {
    impl_->detector = impl_->descriptor = orb();
  } else if (p.detector == "fast_orb") {
    impl_->detector = cv::FastFeatureDetector::create(p.fast_threshold, true);
    impl_->descriptor = orb();
  } else if (p.detector == "akaze") {
    impl_->detector = impl_->descriptor = cv::AKAZE::create();
  } else if (p.detector == "brisk") {
    impl_->detector = impl_->descriptor = cv::BRISK::create(p.fast_threshold * 2);
  } else {
    throw InputError("keypoints.detector",
                     "unknown detector '" + p.detector + "' (orb, fast_orb, akaze, brisk)");
  }
}

KeypointExtractor::~KeypointExtractor() = default;
KeypointExtractor::KeypointExtractor(KeypointExtractor&&) noexcept = default;
KeypointExtractor& KeypointExtractor::operator=(KeypointExtractor&&) noexcept = default;

namespace {
/// Sub-pixel refinement: fit a parabola through the smoothed image's 3x3 neighbourhood in each
/// axis when the keypoint sits on a local intensity maximum (radar returns are blobs).
void refineSubpixel(const cv::Mat& smooth, std::vector<cv::KeyPoint>& pts) {
  for (auto& kp : pts) {
    const int c = cvRound(kp.pt.x), r = cvRound(kp.pt.y);
    if (c < 1 || r < 1 || c >= smooth.cols - 1 || r >= smooth.rows - 1) continue;
    const float v = smooth.at<float>(r, c);
    const float l = smooth.at<float>(r, c - 1), rr = smooth.at<float>(r, c + 1);
    const float u = smooth.at<float>(r - 1, c), d = smooth.at<float>(r + 1, c);
    const float dx2 = l - 2 * v + rr, dy2 = u - 2 * v + d;
    float ox = 0.f, oy = 0.f;
    if (dx2 < 0) ox = std::clamp(0.5f * (l - rr) / dx2, -0.5f, 0.5f);
    if (dy2 < 0) oy = std::clamp(0.5f * (u - d) / dy2, -0.5f, 0.5f);
    kp.pt = cv::Point2f(static_cast<float>(c) + ox, static_cast<float>(r) + oy);
  }
}
}  // namespace

std::vector<cv::KeyPoint> KeypointExtractor::detect(const cv::Mat& image, const cv::Mat& mask) const {
  cv::Mat input = image;
  if (params_.blur_sigma_px > 0) cv::GaussianBlur(image, input, cv::Size(), params_.blur_sigma_px);
  std::vector<cv::KeyPoint> pts;
  impl_->detector->detect(input, pts, mask);
  if (params_.detector == "fast_orb" && static_cast<int>(pts.size()) > params_.max_keypoints)
    cv::KeyPointsFilter::retainBest(pts, params_.max_keypoints);
  return pts;
}

ImageKeypoints KeypointExtractor::describe(const cv::Mat& image, std::vector<cv::KeyPoint> points) const {
  ImageKeypoints out;
  cv::Mat input = image;
  if (params_.blur_sigma_px > 0) cv::GaussianBlur(image, input, cv::Size(), params_.blur_sigma_px);
  impl_->descriptor->compute(input, points, out.descriptors);
  out.norm_type = impl_->descriptor->defaultNorm();
  if (params_.subpixel && !points.empty()) {
    cv::Mat smooth;
    input.convertTo(smooth, CV_32F);
    cv::GaussianBlur(smooth, smooth, cv::Size(5, 5), 1.0);
    refineSubpixel(smooth, points);
  }
  out.points = std::move(points);
  return out;
}

ImageKeypoints KeypointExtractor::extract(const cv::Mat& image, const cv::Mat& mask) const {
  return describe(image, detect(image, mask));
}

}  // namespace radarslam
