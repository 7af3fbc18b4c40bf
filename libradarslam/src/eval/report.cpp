#include "radarslam/eval/report.h"

#include <cmath>
#include <cstdio>
#include <numbers>

#include "radarslam/core/atomic_file.h"

namespace radarslam::eval {

namespace {

std::string fmt(const char* format, double v) {
  if (!std::isfinite(v)) return "n/a";
  char buf[64];
  std::snprintf(buf, sizeof(buf), format, v);
  return buf;
}

std::string padLeft(const std::string& s, std::size_t width) {
  return s.size() >= width ? s : std::string(width - s.size(), ' ') + s;
}

// ---- JSON ------------------------------------------------------------------------------------
std::string jsonString(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\r':
        out += "\\r";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof(buf), "\\u%04x", c);
          out += buf;
        } else
          out += c;
    }
  }
  return out + "\"";
}

std::string jsonNumber(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.10g", v);
  return buf;
}

/// A tiny JSON writer with two-space indentation; keys are written in call order.
class Json {
 public:
  Json& open(const std::string& key, char bracket) {
    item(key);
    out_ += bracket;
    first_ = true;
    ++depth_;
    return *this;
  }
  Json& close(char bracket) {
    --depth_;
    out_.append("\n").append(2 * static_cast<std::size_t>(depth_), ' ').push_back(bracket);
    first_ = false;
    return *this;
  }
  Json& num(const std::string& key, double v) { return raw(key, jsonNumber(v)); }
  Json& count(const std::string& key, std::size_t v) { return raw(key, std::to_string(v)); }
  Json& str(const std::string& key, const std::string& v) { return raw(key, jsonString(v)); }
  Json& raw(const std::string& key, const std::string& v) {
    item(key);
    out_ += v;
    return *this;
  }
  std::string text() const { return out_ + "\n"; }

 private:
  void item(const std::string& key) {
    if (depth_ > 0) {
      if (!first_) out_ += ",";
      out_.append("\n").append(2 * static_cast<std::size_t>(depth_), ' ');
      if (!key.empty()) out_.append(jsonString(key)).append(": ");
    }
    first_ = false;
  }
  std::string out_;
  int depth_ = 0;
  bool first_ = true;
};

void statsJson(Json& j, const std::string& key, const ErrorStats& s) {
  j.open(key, '{')
      .count("count", s.count)
      .num("rmse", s.rmse)
      .num("mean", s.mean)
      .num("median", s.median)
      .num("std", s.std)
      .num("min", s.min)
      .num("max", s.max)
      .close('}');
}

}  // namespace

std::string formatSummary(const EvalReport& r) {
  const Association& a = r.association;
  const KittiResult& k = r.kitti;
  std::string s;
  s += "radarslam eval: " + r.est_label + "  vs  " + r.gt_label + "\n";
  s += "  poses          " + std::to_string(r.est_poses) + " estimated, " + std::to_string(a.size()) +
       " matched to " + std::to_string(r.gt_poses) + " ground-truth poses";
  if (a.dropped() > 0)
    s += " (dropped " + std::to_string(a.dropped()) + ": " + std::to_string(a.dropped_before_gt) +
         " before, " + std::to_string(a.dropped_after_gt) + " after, " +
         std::to_string(a.dropped_in_gt_gaps) + " in gaps)";
  s += "\n";
  s += "  path           " + fmt("%.1f", r.gt_path_length_m) + " m ground truth, " +
       fmt("%.1f", r.est_path_length_m) + " m estimated, over " + fmt("%.1f", r.duration_s) + " s\n";
  if (k.valid()) {
    s += "  KITTI          translation " + fmt("%.3f", k.t_err_percent) + " %   rotation " +
         fmt("%.4f", k.r_err_deg_per_m) + " deg/m = " + fmt("%.3f", k.r_err_deg_per_100m) + " deg/100m   (" +
         std::to_string(k.segments) + " segments, start every " + std::to_string(r.params.kitti.step_frames) +
         " frames)\n";
    std::string l = "    length [m]  ", t = "    t [%]       ", rr = "    r [deg/100m]";
    for (const auto& pl : k.per_length) {
      l += padLeft(fmt("%.0f", pl.length_m), 8);
      t += padLeft(fmt("%.3f", pl.t_err_percent), 8);
      rr += padLeft(fmt("%.3f", pl.r_err_deg_per_100m), 8);
    }
    s += l + "\n" + t + "\n" + rr + "\n";
  } else {
    s += "  KITTI          n/a: the ground-truth path (" + fmt("%.1f", r.gt_path_length_m) +
         " m) has no segment of " +
         (r.params.kitti.lengths_m.empty() ? std::string("any length")
                                           : fmt("%.0f", r.params.kitti.lengths_m[0]) + " m") +
         "\n";
  }
  s += "  ATE            RMSE " + fmt("%.3f", r.ate.trans_m.rmse) + " m (mean " +
       fmt("%.3f", r.ate.trans_m.mean) + ", median " + fmt("%.3f", r.ate.trans_m.median) + ", max " +
       fmt("%.3f", r.ate.trans_m.max) + ")   rotation RMSE " + fmt("%.3f", r.ate.rot_deg.rmse) +
       " deg   (after SE(2) alignment)\n";
  s += "  RPE per frame  translation RMSE " + fmt("%.4f", r.rpe.trans_m.rmse) + " m (mean " +
       fmt("%.4f", r.rpe.trans_m.mean) + ", max " + fmt("%.4f", r.rpe.trans_m.max) + ")   rotation RMSE " +
       fmt("%.4f", r.rpe.rot_deg.rmse) + " deg (mean " + fmt("%.4f", r.rpe.rot_deg.mean) + ", max " +
       fmt("%.4f", r.rpe.rot_deg.max) + ")\n";
  return s;
}

std::string toJson(const EvalReport& r) {
  const Association& a = r.association;
  const KittiResult& k = r.kitti;
  Json j;
  j.open("", '{').count("format_version", 1);
  j.open("estimate", '{').str("label", r.est_label).count("poses", r.est_poses).close('}');
  j.open("ground_truth", '{').str("label", r.gt_label).count("poses", r.gt_poses).close('}');
  j.open("association", '{')
      .count("matched", a.size())
      .count("dropped_before_gt", a.dropped_before_gt)
      .count("dropped_after_gt", a.dropped_after_gt)
      .count("dropped_in_gt_gaps", a.dropped_in_gt_gaps)
      .num("max_gt_gap_s", r.params.max_gt_gap_s)
      .close('}');
  j.num("gt_path_length_m", r.gt_path_length_m).num("est_path_length_m", r.est_path_length_m);
  j.num("duration_s", r.duration_s);
  j.open("kitti", '{').count("step_frames", r.params.kitti.step_frames);
  j.open("lengths_m", '[');
  for (double l : r.params.kitti.lengths_m) j.num("", l);
  j.close(']');
  j.count("segments", k.segments)
      .num("t_err_percent", k.t_err_percent)
      .num("r_err_deg_per_m", k.r_err_deg_per_m)
      .num("r_err_deg_per_100m", k.r_err_deg_per_100m);
  j.open("per_length", '[');
  for (const auto& pl : k.per_length)
    j.open("", '{')
        .num("length_m", pl.length_m)
        .count("segments", pl.segments)
        .num("t_err_percent", pl.t_err_percent)
        .num("r_err_deg_per_100m", pl.r_err_deg_per_100m)
        .close('}');
  j.close(']').close('}');
  j.open("ate", '{');
  j.open("alignment", '{')
      .num("x_m", r.ate.alignment.x)
      .num("y_m", r.ate.alignment.y)
      .num("yaw_deg", r.ate.alignment.phi * 180.0 / std::numbers::pi)
      .close('}');
  statsJson(j, "trans_m", r.ate.trans_m);
  statsJson(j, "rot_deg", r.ate.rot_deg);
  j.close('}');
  j.open("rpe", '{');
  statsJson(j, "trans_m", r.rpe.trans_m);
  statsJson(j, "rot_deg", r.rpe.rot_deg);
  j.close('}');
  j.close('}');
  return j.text();
}

void writeJsonReport(const std::filesystem::path& file, const EvalReport& report) {
  writeTextAtomically(file, toJson(report));
}

}  // namespace radarslam::eval
