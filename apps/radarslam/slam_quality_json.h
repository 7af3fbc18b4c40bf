#pragma once
// eval/slam_quality.json of `radarslam map`: odometry and SLAM accuracy, loop truth and map
// self-consistency in one small machine-readable file (what scripts/bench.py collects).
#include <radarslam/eval/evaluate.h>
#include <radarslam/slam/loop_evaluation.h>
#include <radarslam/slam/map_consistency.h>

#include <string>

namespace radarslam {

std::string slamQualityJson(const eval::EvalReport& slam, const eval::EvalReport& odometry,
                            const LoopEvaluation& loops, const MapConsistency& consistency);

}  // namespace radarslam
