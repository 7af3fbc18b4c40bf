#pragma once
// `radarslam localize` evaluation: the dataset's ground truth in the map's frame, and errors of
// localised poses against it, absolute and relative to the map (docs/localization.md).
#include <mrpt/math/TPose2D.h>

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <radarslam/core/trajectory.h>
#include <radarslam/io/dataset.h>
#include <radarslam/map/keyframe_map.h>

namespace radarslam::cli {

/// Ground truth in the map frame. Dataset readers give it in the dataset's own frame (e.g. Oxford:
/// chained from the first scan), not the map's. When both the map's source dataset and DIR have
/// absolute truth (gt/poses.tum, written by the simulator), or the map was built from DIR itself,
/// the map frame is fitted to the truth at the map's keyframes (least-squares SE(2),
/// eval::alignSE2): exact for a map-synth map, the best-fit frame for a SLAM map, whose own error
/// then shows as the fit residual. Otherwise the frames are not comparable (nullopt).
struct MapFrameTruth {
  Trajectory truth;  ///< the dataset's scans, in the map frame
  /// Per map keyframe: its true pose in the map frame (nullopt where the truth has no pose).
  std::vector<std::optional<mrpt::math::TPose2D>> keyframe_truth;
  std::string how;  ///< for the summary
};

std::optional<MapFrameTruth> truthInMapFrame(const KeyframeMap& map, const DatasetReader& reader,
                                             const std::filesystem::path& dir);

/// Position (m) and heading (deg) error of `est` relative to the map: its pose in the frame of the
/// nearest map keyframe with truth, against the true pose in that keyframe's true frame. The map's
/// own error (drift of a SLAM map) does not enter; this is what a client using the map sees.
std::optional<std::pair<double, double>> mapRelativeError(const KeyframeMap& map, const MapFrameTruth& truth,
                                                          const mrpt::math::TPose2D& est,
                                                          const mrpt::math::TPose2D& est_truth);
/// The true pose as the map places it: the nearest map keyframe (with truth) of `est` composed with
/// the true pose relative to that keyframe's true pose. `est` minus this is mapRelativeError's
/// error in the map frame; the consistency (NEES) of a localiser in a SLAM map is measured against
/// it, since the map's own drift is not the localiser's error.
std::optional<mrpt::math::TPose2D> mapRelativeTruth(const KeyframeMap& map, const MapFrameTruth& truth,
                                                    const mrpt::math::TPose2D& est,
                                                    const mrpt::math::TPose2D& est_truth);

}  // namespace radarslam::cli
