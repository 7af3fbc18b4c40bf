#pragma once
// Plots of an EvalReport, each written twice: as SVG (vector, for documents) and as PNG (rendered
// with OpenCV, white background, anti-aliased). `stem` is the output path without extension.
#include <filesystem>
#include <string>
#include <vector>

#include "radarslam/eval/evaluate.h"

namespace radarslam::eval {

/// Estimate (after the ATE alignment) over ground truth, equal axis scale, metre grid, start and
/// end markers, legend. Returns the files written ({stem}.svg, {stem}.png).
std::vector<std::filesystem::path> writeTrajectoryPlot(const std::filesystem::path& stem,
                                                       const EvalReport& report);

/// KITTI errors per segment length: translational % and rotational deg/100 m, as bars.
std::vector<std::filesystem::path> writeSegmentErrorPlot(const std::filesystem::path& stem,
                                                         const EvalReport& report);

/// Both plots into `dir` as trajectory.{svg,png} and segment_errors.{svg,png}.
std::vector<std::filesystem::path> writePlots(const std::filesystem::path& dir, const EvalReport& report);

}  // namespace radarslam::eval
