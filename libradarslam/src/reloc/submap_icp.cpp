// Local submap and robust point-to-line/point-to-point ICP; see reloc/submap_icp.h.
#include "radarslam/reloc/submap_icp.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>

#include "radarslam/core/errors.h"
#include "radarslam/core/yaml_params.h"
#include "radarslam/loop/point_index_2d.h"

namespace radarslam {

void loadParams(const YamlParams& yaml, SubmapParams& p) {
  yaml.get("radius_m", p.radius_m, Range::above(0, 10000.0));
  yaml.get("voxel_m", p.voxel_m, Range::closed(0.01, 100));
  yaml.get("max_point_range_m", p.max_point_range_m, Range::closed(0, 10000.0));
  yaml.get("rebuild_distance_m", p.rebuild_distance_m, Range::closed(0, 10000.0));
  yaml.get("max_path_m", p.max_path_m, Range::closed(0, 1000000.0));
}

void loadParams(const YamlParams& yaml, IcpParams& p) {
  yaml.get("max_iterations", p.max_iterations, Range::closed(1, 1000));
  yaml.get("max_correspondence_m", p.max_correspondence_m, Range::above(0, 1000));
  yaml.get("inlier_distance_m", p.inlier_distance_m, Range::above(0, 1000));
  yaml.get("cauchy_m", p.cauchy_m, Range::above(0, 100));
  yaml.get("normal_radius_m", p.normal_radius_m, Range::above(0, 100));
  yaml.get("max_planarity", p.max_planarity, Range::closed(0, 1));
  yaml.get("convergence_m", p.convergence_m, Range::closed(0, 10));
  yaml.get("convergence_rad", p.convergence_rad, Range::closed(0, 1));
  yaml.get("scan_voxel_m", p.scan_voxel_m, Range::closed(0, 100));
  int max_points = static_cast<int>(p.max_scan_points);
  yaml.get("max_scan_points", max_points, Range::closed(10, 1000000.0));
  yaml.get("min_sigma_m", p.min_sigma_m, Range::closed(0, 100));
  yaml.get("covariance_scale", p.covariance_scale, Range::above(0, 1000000.0));
  yaml.get("heading_sigma_floor_deg", p.heading_sigma_floor_deg, Range::closed(0, 90));
  yaml.get("position_sigma_floor_m", p.position_sigma_floor_m, Range::closed(0, 100));
  yaml.get("slam_map_heading_sigma_floor_deg", p.slam_map_heading_sigma_floor_deg, Range::closed(0, 90));
  yaml.get("slam_map_position_sigma_floor_m", p.slam_map_position_sigma_floor_m, Range::closed(0, 100));
  yaml.get("profile_shift_m", p.profile_shift_m, Range::closed(0, 100));
  if (p.max_correspondence_m < p.inlier_distance_m)
    yaml.fail("max_correspondence_m", "must be >= inlier_distance_m");
  p.max_scan_points = static_cast<std::size_t>(max_points);
}

namespace {

using Vec2 = Eigen::Vector2d;

std::int64_t voxelKey(double x, double y, double voxel) {
  const auto ix = static_cast<std::int64_t>(std::floor(x / voxel));
  const auto iy = static_cast<std::int64_t>(std::floor(y / voxel));
  return (ix << 32) ^ (iy & 0xffffffffLL);
}

/// The Cauchy loss whose IRLS weight the registration uses: rho(r) = c^2 / 2 log(1 + r^2 / c^2).
double cauchyLoss(double r2, double c2) { return 0.5 * c2 * std::log1p(r2 / c2); }

/// One point per voxel: the centroid of the points in it.
std::vector<Vec2> voxelCentroids(const std::vector<Vec2>& pts, double voxel) {
  std::unordered_map<std::int64_t, std::size_t> index;
  index.reserve(pts.size());
  std::vector<Vec2> sum;
  std::vector<int> count;
  for (const auto& p : pts) {
    const auto [it, inserted] = index.emplace(voxelKey(p.x(), p.y(), voxel), sum.size());
    if (inserted) {
      sum.push_back(p);
      count.push_back(1);
    } else {
      sum[it->second] += p;
      ++count[it->second];
    }
  }
  for (std::size_t i = 0; i < sum.size(); ++i) sum[i] /= count[i];
  return sum;
}

}  // namespace

std::vector<RadarPoint> toRadarPoints(const std::vector<KeyframePoint>& pts) {
  std::vector<RadarPoint> out;
  out.reserve(pts.size());
  for (const auto& p : pts) {
    RadarPoint r;
    r.x = p.x, r.y = p.y, r.power = p.power;
    r.range_m = std::hypot(p.x, p.y);
    out.push_back(r);
  }
  return out;
}

std::vector<Vec2> LocalSubmap::thinScan(std::span<const RadarPoint> c, const IcpParams& params) {
  const double voxel = params.scan_voxel_m;
  const std::size_t max_points = params.max_scan_points;
  std::vector<Vec2> out;
  if (voxel > 0) {
    std::unordered_map<std::int64_t, std::size_t> best;
    best.reserve(c.size());
    std::vector<std::size_t> order;
    for (std::size_t i = 0; i < c.size(); ++i) {
      const auto [it, inserted] = best.emplace(voxelKey(c[i].x, c[i].y, voxel), i);
      if (inserted)
        order.push_back(i);
      else if (c[i].power > c[it->second].power)
        it->second = i;
    }
    // Deterministic order: by first appearance of the voxel.
    for (const std::size_t first : order) {
      const std::size_t i = best.at(voxelKey(c[first].x, c[first].y, voxel));
      out.emplace_back(c[i].x, c[i].y);
    }
  } else {
    for (const auto& p : c) out.emplace_back(p.x, p.y);
  }
  if (out.size() > max_points) {
    std::vector<Vec2> s;
    s.reserve(max_points);
    for (std::size_t k = 0; k < max_points; ++k) s.push_back(out[k * out.size() / max_points]);
    out.swap(s);
  }
  return out;
}

struct LocalSubmap::Impl {
  PointIndex2D index;
  // Lazily computed line normals: 0 = not computed, 1 = line (normal valid), 2 = not a line.
  mutable std::vector<std::uint8_t> normal_state;
  mutable std::vector<Vec2> normal;
  explicit Impl(std::vector<Vec2> p) : index(std::move(p)) {
    normal_state.assign(index.size(), 0);
    normal.resize(index.size());
  }

  /// The line normal at submap point i, or nullptr if its neighbourhood is not linear.
  const Vec2* lineNormal(std::uint32_t i, const IcpParams& params) const {
    if (normal_state[i] == 0) {
      std::vector<std::pair<std::uint32_t, double>> nb;
      index.within(index.points()[i], params.normal_radius_m, nb);
      normal_state[i] = 2;
      if (nb.size() >= 4) {
        Vec2 mean = Vec2::Zero();
        for (const auto& [j, d] : nb) mean += index.points()[j];
        mean /= static_cast<double>(nb.size());
        Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
        for (const auto& [j, d] : nb) {
          const Vec2 e = index.points()[j] - mean;
          cov += e * e.transpose();
        }
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(cov);
        const double l0 = es.eigenvalues()(0), l1 = es.eigenvalues()(1);
        if (l1 > 0 && l0 <= params.max_planarity * l1) {
          normal[i] = es.eigenvectors().col(0).normalized();
          normal_state[i] = 1;
        }
      }
    }
    return normal_state[i] == 1 ? &normal[i] : nullptr;
  }

  /// A placed scan point's share of IcpResult::cost with the final pass's gate (gate2 squared);
  /// `inlier`: whether it lies within the gate.
  double pointCost(const Vec2& q, double gate2, const IcpParams& params, bool& inlier) const {
    const double c2 = params.cauchy_m * params.cauchy_m;
    const auto [d2, idx] = index.nearest(q);
    inlier = d2 <= gate2;
    if (!inlier) return cauchyLoss(gate2, c2);
    if (const Vec2* n = lineNormal(idx, params)) {
      const double r = n->dot(q - index.points()[idx]);
      return cauchyLoss(r * r, c2);
    }
    return cauchyLoss(d2, c2);
  }
};

LocalSubmap::LocalSubmap() = default;
LocalSubmap::~LocalSubmap() = default;
LocalSubmap::LocalSubmap(LocalSubmap&&) noexcept = default;
LocalSubmap& LocalSubmap::operator=(LocalSubmap&&) noexcept = default;

std::size_t LocalSubmap::size() const { return impl_ ? impl_->index.size() : 0; }

LocalSubmap LocalSubmap::build(const KeyframeMap& map, double cx, double cy, const SubmapParams& params,
                               const std::vector<char>* allowed) {
  std::vector<Vec2> pts;
  std::vector<std::size_t> used;
  const double r2 = params.radius_m * params.radius_m;
  const double range2 = params.max_point_range_m * params.max_point_range_m;
  for (std::size_t k = 0; k < map.keyframes.size(); ++k) {
    const Keyframe& kf = map.keyframes[k];
    const double dx = kf.pose.x - cx, dy = kf.pose.y - cy;
    if (dx * dx + dy * dy > r2 || (allowed && (k >= allowed->size() || !(*allowed)[k]))) continue;
    used.push_back(k);
    const double c = std::cos(kf.pose.phi), s = std::sin(kf.pose.phi);
    for (const auto& p : kf.points) {
      if (range2 > 0 && double(p.x) * p.x + double(p.y) * p.y > range2) continue;
      pts.emplace_back(kf.pose.x + c * p.x - s * p.y, kf.pose.y + s * p.x + c * p.y);
    }
  }
  LocalSubmap m = fromPoints(std::move(pts), params.voxel_m);
  m.keyframe_indices_ = std::move(used);
  m.cx_ = cx;
  m.cy_ = cy;
  return m;
}

LocalSubmap LocalSubmap::fromPoints(std::vector<Eigen::Vector2d> map_points, double voxel_m) {
  LocalSubmap m;
  m.impl_ = std::make_unique<Impl>(voxel_m > 0 ? voxelCentroids(map_points, voxel_m) : std::move(map_points));
  return m;
}

IcpResult LocalSubmap::registerScan(std::span<const RadarPoint> scan, const mrpt::math::TPose2D& initial,
                                    const IcpParams& params, bool fit_profile) const {
  const std::vector<Vec2> thinned = thinScan(scan, params);
  IcpResult res = registerThinned(thinned, initial, params);
  if (fit_profile) fitProfile(thinned, params, res);
  return res;
}

IcpResult LocalSubmap::registerThinned(const std::vector<Vec2>& src, const mrpt::math::TPose2D& initial,
                                       const IcpParams& params) const {
  IcpResult res;
  res.pose = initial;
  res.scan_points = src.size();
  if (!impl_ || impl_->index.size() < 3 || src.size() < 3) return res;

  double x = initial.x, y = initial.y, th = initial.phi;
  Eigen::Matrix3d H;
  double sum_wr2 = 0;
  std::size_t dims = 0, inliers = 0;
  double sum_in_d2 = 0;
  double cost = 0;
  const double c2 = params.cauchy_m * params.cauchy_m;
  auto rho = [c2](double r2) { return cauchyLoss(r2, c2); };  // its IRLS weight is w below
  bool final_pass = false;
  for (int it = 0;; ++it) {
    const double gate =
        final_pass ? params.inlier_distance_m
                   : std::max(params.inlier_distance_m, params.max_correspondence_m * std::pow(0.7, it));
    const double gate2 = gate * gate;
    const double c = std::cos(th), s = std::sin(th);
    H.setZero();
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    sum_wr2 = 0;
    dims = 0;
    inliers = 0;
    sum_in_d2 = 0;
    cost = 0;
    const double outlier_cost = rho(gate2);
    for (const Vec2& p : src) {
      const Vec2 rp(c * p.x() - s * p.y(), s * p.x() + c * p.y());
      const Vec2 q(rp.x() + x, rp.y() + y);
      const auto [d2, idx] = impl_->index.nearest(q);
      if (d2 > gate2) {
        cost += outlier_cost;
        continue;
      }
      ++inliers;
      sum_in_d2 += d2;
      const Vec2 e = q - impl_->index.points()[idx];
      const Vec2 dth(-rp.y(), rp.x());
      if (const Vec2* n = impl_->lineNormal(idx, params)) {
        const double r = n->dot(e);
        const double w = 1.0 / (1.0 + r * r / c2);
        const Eigen::Vector3d J(n->x(), n->y(), n->dot(dth));
        H += w * J * J.transpose();
        g += w * J * r;
        sum_wr2 += w * r * r;
        cost += rho(r * r);
        dims += 1;
      } else {
        const double w = 1.0 / (1.0 + d2 / c2);
        Eigen::Matrix<double, 2, 3> J;
        J << 1, 0, dth.x(), 0, 1, dth.y();
        H += w * J.transpose() * J;
        g += w * J.transpose() * e;
        sum_wr2 += w * d2;
        cost += rho(d2);
        dims += 2;
      }
    }
    if (final_pass || inliers < 3) break;
    const Eigen::Vector3d delta = H.ldlt().solve(-g);
    if (!delta.allFinite()) break;
    x += delta(0), y += delta(1), th += delta(2);
    res.iterations = it + 1;
    const bool small =
        std::hypot(delta(0), delta(1)) < params.convergence_m && std::abs(delta(2)) < params.convergence_rad;
    if ((small && gate <= params.inlier_distance_m) || it + 1 >= params.max_iterations) {
      res.converged = small;
      final_pass = true;  // one more pass: inliers, Hessian and residuals at the solution
    }
  }
  res.pose = {x, y, std::remainder(th, 2 * M_PI)};
  res.inliers = inliers;
  res.fit_score = static_cast<double>(inliers) / static_cast<double>(src.size());
  res.rms_m = inliers > 0 ? std::sqrt(sum_in_d2 / static_cast<double>(inliers)) : 0;
  res.cost = cost;
  const double sigma2 = std::max(params.min_sigma_m * params.min_sigma_m,
                                 dims > 3 ? sum_wr2 / static_cast<double>(dims - 3) : 0.0);
  res.sigma2 = sigma2;
  // sigma^2 H^-1 through the eigen decomposition: a direction the geometry does not constrain (a
  // corridor along its walls) gets a huge variance instead of making the inverse fail.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(0.5 * (H + H.transpose()));
  if (inliers >= 3 && es.info() == Eigen::Success) {
    const Eigen::Vector3d inv_l = es.eigenvalues().cwiseMax(1e-6).cwiseInverse();
    res.covariance = params.covariance_scale * sigma2 * es.eigenvectors() * inv_l.asDiagonal() *
                     es.eigenvectors().transpose();
    res.covariance = 0.5 * (res.covariance + res.covariance.transpose()).eval();
    const double floor_rad = params.heading_sigma_floor_deg * M_PI / 180;
    res.covariance(2, 2) += floor_rad * floor_rad;
    const double floor_m2 = params.position_sigma_floor_m * params.position_sigma_floor_m;
    res.covariance(0, 0) += floor_m2;
    res.covariance(1, 1) += floor_m2;
  } else {
    res.covariance = Eigen::Matrix3d::Identity() * 1e6;
  }
  return res;
}

void LocalSubmap::fitProfile(const std::vector<Vec2>& src, const IcpParams& params, IcpResult& res) const {
  if (params.profile_shift_m <= 0 || res.inliers < 3 || !impl_ || src.empty()) return;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> exy(res.covariance.topLeftCorner<2, 2>());
  res.weak_direction = exy.eigenvectors().col(1).normalized();
  res.profile_fit = 0;
  res.profile_chi2 = std::numeric_limits<double>::infinity();
  const double c = std::cos(res.pose.phi), s = std::sin(res.pose.phi),
               gate2 = params.inlier_distance_m * params.inlier_distance_m;
  // The likelihood ratio of the shifted solution in the registration's calibrated unit (as check (h)
  // compares two alignments, IcpResult::cost).
  const double unit = params.covariance_scale * res.sigma2;
  std::vector<Vec2> placed;  // the scan at the solution
  placed.reserve(src.size());
  for (const Vec2& p : src)
    placed.emplace_back(c * p.x() - s * p.y() + res.pose.x, s * p.x() + c * p.y() + res.pose.y);
  for (const double sign : {-1.0, 1.0}) {
    const Vec2 shift = sign * params.profile_shift_m * res.weak_direction;
    std::size_t n = 0;
    double cost = 0;
    for (const Vec2& q : placed) {
      bool inlier = false;
      cost += impl_->pointCost(q + shift, gate2, params, inlier);
      n += inlier;
    }
    res.profile_fit = std::max(res.profile_fit, static_cast<double>(n) / static_cast<double>(src.size()));
    if (unit > 0) res.profile_chi2 = std::min(res.profile_chi2, 2 * (cost - res.cost) / unit);
  }
}

}  // namespace radarslam
