#include "slam_quality_json.h"

#include <cmath>
#include <cstdio>

namespace radarslam {

namespace {

std::string number(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

/// A JSON string of program text (the loop records' reasons: printable ASCII).
std::string jsonString(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

std::string accuracy(const eval::EvalReport& r) {
  return "{\"kitti_t_percent\": " + number(r.kitti.t_err_percent) +
         ", \"kitti_r_deg_per_m\": " + number(r.kitti.r_err_deg_per_m) +
         ", \"ate_rmse_m\": " + number(r.ate.trans_m.rmse) + ", \"rpe_max_m\": " + number(r.rpe.trans_m.max) +
         ", \"rpe_max_deg\": " + number(r.rpe.rot_deg.max) + ", \"path_m\": " + number(r.gt_path_length_m) +
         "}";
}

std::string pairs(const PairConsistency& p) {
  return "{\"pairs\": " + std::to_string(p.pairs) + ", \"consistent\": " + std::to_string(p.consistent) +
         ", \"fraction\": " + number(p.fraction) + ", \"median_error_m\": " + number(p.median_error_m) +
         ", \"worst_error_m\": " + number(p.worst_error_m) +
         ", \"worst_error_deg\": " + number(p.worst_error_deg) + "}";
}

}  // namespace

std::string slamQualityJson(const eval::EvalReport& slam, const eval::EvalReport& odometry,
                            const LoopEvaluation& loops, const MapConsistency& consistency) {
  std::string s = "{\n  \"odometry\": " + accuracy(odometry) + ",\n  \"slam\": " + accuracy(slam) + ",\n";
  s += "  \"loops\": {\"accepted\": " + std::to_string(loops.accepted) +
       ", \"false_accepted\": " + std::to_string(loops.false_accepted) +
       ", \"false_in_graph\": " + std::to_string(loops.false_in_graph) +
       ", \"recall\": " + number(loops.recall) + ", \"nees_mean\": " + number(loops.nees_mean) +
       ", \"nees_within_95\": " + number(loops.nees_within_95) +
       ", \"slide_accepted\": " + std::to_string(loops.slide_accepted) +
       ", \"slide_false\": " + std::to_string(loops.slide_false) +
       ", \"confirmed_accepted\": " + std::to_string(loops.confirmed_accepted) +
       ", \"confirmed_false\": " + std::to_string(loops.confirmed_false) +
       ", \"keyframes_with_true_loop\": " + std::to_string(loops.keyframes_with_true_loop) +
       ", \"refused_wrong\": " + std::to_string(loops.refused_wrong) + ", \"refused_right\": {";
  for (auto it = loops.refused_right.begin(); it != loops.refused_right.end(); ++it)
    s += (it == loops.refused_right.begin() ? "" : ", ") + jsonString(it->first) + ": " +
         std::to_string(it->second);
  s += "}},\n";
  s += "  \"map_consistency\": {\"revisits\": " + pairs(consistency.revisits) +
       ", \"all\": " + pairs(consistency.all) + "}\n}\n";
  return s;
}

}  // namespace radarslam
