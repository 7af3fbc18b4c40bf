// Scoring of `radarslam localize` side files; see eval_localization.h.
#include "eval_localization.h"

#include <radarslam/core/errors.h>
#include <radarslam/io/trajectory_files.h>
#include <radarslam/reloc/integrity.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <vector>

namespace radarslam::cli {

LocalizationScore scoreLocalization(const std::filesystem::path& side_file, const Trajectory& truth) {
  std::ifstream f(side_file);
  if (!f) throw InputError(side_file.string(), "cannot open the localisation side file");
  LocalizationScore s;
  const double bound95 = chi2Quantile3(0.95);
  double sx = 0, sy = 0, syaw = 0, nees = 0, nees_xy = 0, nees_yaw = 0;
  std::size_t within = 0, trusted_ok = 0, lineno = 0;
  for (std::string line; std::getline(f, line);) {
    ++lineno;
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    std::vector<std::string> c;
    for (std::string w; ss >> w;) c.push_back(w);
    StampNs stamp = 0;
    if (c.size() < 13 || !parseStampText(c[0], stamp))
      throw InputError(side_file.string(), "line " + std::to_string(lineno) +
                                               ": not a radarslam localize side-file row (stamp scan status "
                                               "localised x y phi cov... )");
    ++s.scans;
    const std::string& status = c[2];
    s.tracking += status == "tracking", s.global_fix += status == "global_fix";
    s.degraded += status == "degraded", s.lost += status == "lost";
    if (c[3] != "1") continue;
    ++s.localised;
    const auto t = interpolatePose(truth, stamp);
    if (!t) continue;
    ++s.with_truth;
    double v[9];
    for (int i = 0; i < 9; ++i) v[i] = std::stod(c[4 + i]);
    const Eigen::Vector3d e(v[0] - t->x, v[1] - t->y, std::remainder(v[2] - t->phi, 2 * M_PI));
    Eigen::Matrix3d cov;
    cov << v[3], v[4], v[5], v[4], v[6], v[7], v[5], v[7], v[8];
    sx += e(0) * e(0), sy += e(1) * e(1), syaw += e(2) * e(2);
    const double n = mahalanobis2(e, cov);
    nees += std::isfinite(n) ? n : 1e12;
    within += n <= bound95;
    const Eigen::Matrix2d cxy = cov.topLeftCorner<2, 2>();
    const Eigen::LLT<Eigen::Matrix2d> llt(cxy);
    nees_xy += llt.info() == Eigen::Success ? e.head<2>().dot(llt.solve(e.head<2>().eval())) : 1e12;
    nees_yaw += cov(2, 2) > 0 ? e(2) * e(2) / cov(2, 2) : 1e12;
    const double pos = std::hypot(e(0), e(1)), yaw_deg = std::abs(e(2)) * 180 / M_PI;
    const bool far = pos > 2.0 || yaw_deg > 2.0;
    if (status == "tracking" || status == "global_fix") {
      ++s.trusted;
      trusted_ok += pos <= 0.3 && yaw_deg <= 0.5;
      s.trusted_far_off += far;
    } else {
      s.degraded_far_off += far;
    }
  }
  if (s.with_truth > 0) {
    const double n = static_cast<double>(s.with_truth);
    s.rmse_x_m = std::sqrt(sx / n), s.rmse_y_m = std::sqrt(sy / n),
    s.rmse_yaw_deg = std::sqrt(syaw / n) * 180 / M_PI;
    s.nees_mean = nees / n;
    s.nees_within_95 = within / n;
    s.nees_xy_mean = nees_xy / n, s.nees_yaw_mean = nees_yaw / n;
  }
  if (s.trusted > 0) s.trusted_within = static_cast<double>(trusted_ok) / static_cast<double>(s.trusted);
  return s;
}

std::string formatLocalizationScore(const LocalizationScore& s) {
  char buf[1024];
  std::snprintf(
      buf, sizeof buf,
      "radarslam eval --localization\n"
      "  scans          %zu: tracking %zu, global_fix %zu, degraded %zu, lost %zu; %zu localised, %zu "
      "with ground truth\n"
      "  RMSE           x %.3f m, y %.3f m, yaw %.3f deg (localised scans)\n"
      "  consistency    NEES mean %.2f (3 if calibrated), %.1f %% within the chi2(3) 95 %% bound; position "
      "part "
      "%.2f (2 if calibrated), heading part %.2f (1)\n"
      "  trusted        %zu tracking/global_fix: %.1f %% within 0.3 m / 0.5 deg, %zu > 2 m or 2 deg "
      "off\n"
      "  degraded       %zu > 2 m or 2 deg off\n",
      s.scans, s.tracking, s.global_fix, s.degraded, s.lost, s.localised, s.with_truth, s.rmse_x_m,
      s.rmse_y_m, s.rmse_yaw_deg, s.nees_mean, 100 * s.nees_within_95, s.nees_xy_mean, s.nees_yaw_mean,
      s.trusted, 100 * s.trusted_within, s.trusted_far_off, s.degraded_far_off);
  return buf;
}

std::string localizationScoreJson(const LocalizationScore& s, const std::string& est, const std::string& gt) {
  auto quote = [](const std::string& x) {
    std::string o = "\"";
    for (char ch : x) {
      if (ch == '"' || ch == '\\') o += '\\';
      o += ch;
    }
    return o + "\"";
  };
  char buf[1024];
  std::snprintf(buf, sizeof buf,
                "  \"scans\": %zu,\n  \"tracking\": %zu,\n  \"global_fix\": %zu,\n  \"degraded\": %zu,\n"
                "  \"lost\": %zu,\n  \"localised\": %zu,\n  \"with_truth\": %zu,\n  \"rmse_x_m\": %.6f,\n"
                "  \"rmse_y_m\": %.6f,\n  \"rmse_yaw_deg\": %.6f,\n  \"nees_mean\": %.6f,\n"
                "  \"nees_within_chi2_95\": %.6f,\n  \"nees_xy_mean\": %.6f,\n  \"nees_yaw_mean\": %.6f,\n"
                "  \"trusted\": %zu,\n  \"trusted_within_0p3m_0p5deg\": %.6f,\n"
                "  \"trusted_far_off\": %zu,\n  \"degraded_far_off\": %zu\n",
                s.scans, s.tracking, s.global_fix, s.degraded, s.lost, s.localised, s.with_truth, s.rmse_x_m,
                s.rmse_y_m, s.rmse_yaw_deg, s.nees_mean, s.nees_within_95, s.nees_xy_mean, s.nees_yaw_mean,
                s.trusted, s.trusted_within, s.trusted_far_off, s.degraded_far_off);
  return "{\n  \"mode\": \"localization\",\n  \"estimate\": " + quote(est) +
         ",\n  \"ground_truth\": " + quote(gt) + ",\n" + buf + "}\n";
}

}  // namespace radarslam::cli
