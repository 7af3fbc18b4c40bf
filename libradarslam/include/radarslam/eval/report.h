#pragma once
// Human and machine readable forms of an EvalReport.
#include <filesystem>
#include <string>

#include "radarslam/eval/evaluate.h"

namespace radarslam::eval {

/// A few aligned lines for the terminal: counts, KITTI t% / r deg/100m (+ per length), ATE, RPE.
std::string formatSummary(const EvalReport& report);

/// The whole report as JSON (metrics that do not exist, e.g. KITTI on a path < 100 m, are null).
std::string toJson(const EvalReport& report);
void writeJsonReport(const std::filesystem::path& file, const EvalReport& report);

}  // namespace radarslam::eval
