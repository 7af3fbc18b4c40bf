#pragma once
// Sub-pixel correspondence refinement (ours, not in the paper): a matched keypoint pair only
// says the two features are "about here" (detector jitter ~1 px = 0.25 m). Aligning the
// keyframe's image patch around its keypoint with the current image near the matched keypoint
// finds where the same piece of the scene really is in the current image, to a fraction of a
// pixel: exhaustive NCC over integer offsets, then a few translational Lucas-Kanade steps.
#include <opencv2/core/mat.hpp>
#include <opencv2/core/types.hpp>

namespace radarslam {

struct PatchAlignParams {
  bool enabled = true;
  int patch_radius_px = 6;     ///< patch is (2r+1)^2; valid [1, 32]
  int search_radius_px = 2;    ///< integer offsets searched around the initial position; valid [0, 32]
  int lk_iterations = 3;       ///< valid [0, 100]
  double min_ncc = 0.6;        ///< below this the pair is left unrefined and flagged; valid [-1, 1]
  double blur_sigma_px = 1.5;  ///< valid [0, 20]
  /// After the first pose, also track every other keyframe keypoint into the current image.
  bool track_keyframe_points = true;
  int track_search_radius_px = 1;  ///< valid [0, 32]
  double track_gate_m =
      0.5;  ///< tracked points farther than this from the estimate are dropped; valid (0, 100]
};

/// Image prepared for alignment (smoothed, float).
struct AlignImage {
  cv::Mat smooth;
};

AlignImage prepareAlignImage(const cv::Mat& image8u, const PatchAlignParams& params);

struct PatchAlignResult {
  cv::Point2f position;  ///< refined position in the current image
  double ncc = 0.0;
  bool ok = false;
};

/// Where the patch of `ref` centred at `ref_pt` lies in `cur`, searching around `cur_pt`.
PatchAlignResult alignPatch(const AlignImage& ref, cv::Point2f ref_pt, const AlignImage& cur,
                            cv::Point2f cur_pt, const PatchAlignParams& params);

}  // namespace radarslam
