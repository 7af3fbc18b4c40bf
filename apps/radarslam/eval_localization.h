#pragma once
// `radarslam eval --localization EST.csv GT` (issue #14): scores the per-scan side file of
// `radarslam localize` against ground truth in the map frame: RMSE of x, y, yaw over the localised
// scans, consistency (NEES of (x, y, yaw) with the reported covariance: mean, ideally 3, and the
// fraction within the chi^2(3) 95 % bound), and per status the scans within 0.3 m / 0.5 deg and
// those > 2 m or 2 deg off.
#include <radarslam/core/trajectory.h>

#include <filesystem>
#include <string>

namespace radarslam::cli {

struct LocalizationScore {
  std::size_t scans = 0, localised = 0, with_truth = 0;
  std::size_t tracking = 0, global_fix = 0, degraded = 0, lost = 0;
  double rmse_x_m = 0, rmse_y_m = 0, rmse_yaw_deg = 0;
  double nees_mean = 0, nees_within_95 = 0;    ///< over the localised scans with truth
  double nees_xy_mean = 0, nees_yaw_mean = 0;  ///< the position (2 dof) and heading (1 dof) parts
  std::size_t trusted = 0;                     ///< tracking + global_fix with truth
  double trusted_within = 0;                   ///< fraction of `trusted` within 0.3 m and 0.5 deg
  std::size_t trusted_far_off = 0;             ///< trusted scans > 2 m or > 2 deg off
  std::size_t degraded_far_off = 0;            ///< degraded scans > 2 m or > 2 deg off
};

/// Throws InputError on a malformed side file.
LocalizationScore scoreLocalization(const std::filesystem::path& side_file, const Trajectory& truth);
std::string formatLocalizationScore(const LocalizationScore& s);
std::string localizationScoreJson(const LocalizationScore& s, const std::string& est, const std::string& gt);

}  // namespace radarslam::cli
