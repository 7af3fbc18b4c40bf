// Per-scan benchmark outputs of `radarslam localize`; see localize_output.h.
#include "localize_output.h"

#include <radarslam/io/trajectory_files.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>

namespace radarslam::cli {

namespace {
Eigen::Matrix3d information(const Eigen::Matrix3d& cov) {
  const Eigen::Matrix3d s = 0.5 * (cov + cov.transpose());
  const Eigen::LDLT<Eigen::Matrix3d> ldlt(s);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) return Eigen::Matrix3d::Zero();
  return ldlt.solve(Eigen::Matrix3d::Identity());
}
}  // namespace

const char* const kSideFileExtraHeader =
    "keyframe_id keyframe_stamp_s kf_x kf_y kf_phi info_xx info_xy info_xphi info_yy info_yphi info_phiphi "
    "check";

KeyframeRelativePose relativeToKeyframe(const KeyframeMap& map, const LocalizationResult& r) {
  KeyframeRelativePose out;
  if (!r.localised || r.keyframe < 0 || static_cast<std::size_t>(r.keyframe) >= map.keyframes.size())
    return out;
  const auto& kf = map.keyframes[static_cast<std::size_t>(r.keyframe)].pose;
  const double c = std::cos(kf.phi), s = std::sin(kf.phi);
  const double dx = r.pose.x - kf.x, dy = r.pose.y - kf.y;
  out.pose = {c * dx + s * dy, -s * dx + c * dy, std::remainder(r.pose.phi - kf.phi, 2 * M_PI)};
  Eigen::Matrix3d rot = Eigen::Matrix3d::Identity();
  rot(0, 0) = c, rot(0, 1) = s, rot(1, 0) = -s, rot(1, 1) = c;  // map -> keyframe frame (the map is fixed)
  out.covariance = rot * r.covariance * rot.transpose();
  return out;
}

std::string sideFileExtra(const KeyframeMap& map, const LocalizationResult& r) {
  char buf[384];
  const std::string check = r.check.empty() ? "-" : r.check;
  if (!r.localised || r.keyframe < 0) {
    std::snprintf(buf, sizeof buf, "-1 nan nan nan nan 0 0 0 0 0 0 %s", check.c_str());
    return buf;
  }
  const auto& kf = map.keyframes[static_cast<std::size_t>(r.keyframe)];
  const KeyframeRelativePose rel = relativeToKeyframe(map, r);
  const Eigen::Matrix3d info = information(r.covariance);
  std::snprintf(buf, sizeof buf, "%llu %s %.4f %.4f %.6f %.6g %.6g %.6g %.6g %.6g %.6g %s",
                static_cast<unsigned long long>(kf.id), formatStampSeconds(kf.stamp_ns).c_str(), rel.pose.x,
                rel.pose.y, rel.pose.phi, info(0, 0), info(0, 1), info(0, 2), info(1, 1), info(1, 2),
                info(2, 2), check.c_str());
  return buf;
}

std::string boreasRow(const KeyframeMap& map, const LocalizationResult& r) {
  const auto& kf = map.keyframes[static_cast<std::size_t>(r.keyframe)];
  const KeyframeRelativePose rel = relativeToKeyframe(map, r);
  const Eigen::Matrix3d info = information(rel.covariance);
  Eigen::Matrix<double, 6, 6> info6 = Eigen::Matrix<double, 6, 6>::Zero();
  const int idx[3] = {0, 1, 5};  // x, y, rot z
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) info6(idx[i], idx[j]) = info(i, j);
  const double c = std::cos(rel.pose.phi), s = std::sin(rel.pose.phi);
  std::string out = std::to_string(r.stamp / 1000) + " " + std::to_string(kf.stamp_ns / 1000);
  char buf[64];
  const double t[12] = {c, -s, 0, rel.pose.x, s, c, 0, rel.pose.y, 0, 0, 1, 0};
  for (double v : t) std::snprintf(buf, sizeof buf, " %.9g", v), out += buf;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) std::snprintf(buf, sizeof buf, " %.9g", info6(i, j)), out += buf;
  return out + "\n";
}

}  // namespace radarslam::cli
