// M2DP descriptor (He et al. 2016) adapted to planar radar peak clouds; see loop/m2dp.h.
#include "radarslam/loop/m2dp.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "radarslam/core/errors.h"
#include "radarslam/core/yaml_params.h"

namespace radarslam {

void loadParams(const YamlParams& yaml, M2DPParams& params) {
  yaml.get("azimuths", params.azimuths, Range::closed(1, 64));
  yaml.get("elevations", params.elevations, Range::closed(1, 64));
  yaml.get("rings", params.rings, Range::closed(1, 64));
  yaml.get("sectors", params.sectors, Range::closed(1, 64));
  yaml.get("power_height_m", params.power_height_m, Range::closed(0, 1000));
  yaml.get("radius_quantile", params.radius_quantile, Range::above(0, 1));
  int min_points = static_cast<int>(params.min_points);
  yaml.get("min_points", min_points, Range::closed(3, 100000));
  params.min_points = static_cast<std::size_t>(min_points);
}

M2DPDescriptor computeM2DP(std::span<const RadarPoint> cloud, const M2DPParams& params,
                           bool flip_first_axis) {
  const std::size_t n = cloud.size();
  if (n < std::max<std::size_t>(params.min_points, 3)) return {};

  // 1. Centre at the centroid; standardise power as the third coordinate.
  double mx = 0, my = 0, mp = 0;
  for (const auto& p : cloud) mx += p.x, my += p.y, mp += p.power;
  mx /= static_cast<double>(n), my /= static_cast<double>(n), mp /= static_cast<double>(n);
  double sxx = 0, sxy = 0, syy = 0, spp = 0;
  for (const auto& p : cloud) {
    const double dx = p.x - mx, dy = p.y - my, dp = p.power - mp;
    sxx += dx * dx, sxy += dx * dy, syy += dy * dy, spp += dp * dp;
  }
  const double power_std = std::sqrt(spp / static_cast<double>(n));
  const double z_scale = power_std > 1e-9 ? params.power_height_m / power_std : 0.0;

  // 2. PCA of x, y: e1 = the major axis, e2 = e1 rotated by +90 degrees (right-handed).
  Eigen::Matrix2d cov;
  cov << sxx, sxy, sxy, syy;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
  Eigen::Vector2d e1 = eig.eigenvectors().col(1);  // eigenvalues ascending
  if (!(eig.eigenvalues()(1) > 1e-12)) return {};
  double third_moment = 0;
  for (const auto& p : cloud) {
    const double a = e1.x() * (p.x - mx) + e1.y() * (p.y - my);
    third_moment += a * a * a;
  }
  if (third_moment < 0) e1 = -e1;
  if (flip_first_axis) e1 = -e1;
  const Eigen::Vector2d e2(-e1.y(), e1.x());

  std::vector<Eigen::Vector3d> pts(n);
  std::vector<double> dist(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double dx = cloud[i].x - mx, dy = cloud[i].y - my;
    pts[i] = {e1.x() * dx + e1.y() * dy, e2.x() * dx + e2.y() * dy, z_scale * (cloud[i].power - mp)};
    dist[i] = pts[i].norm();
  }

  // 3. Ring radii r, 4r, ..., l^2 r with l^2 r = the radius quantile (M2DP Sec. III-B).
  const std::size_t qi = std::min(
      n - 1, static_cast<std::size_t>(std::floor(params.radius_quantile * static_cast<double>(n - 1))));
  std::nth_element(dist.begin(), dist.begin() + static_cast<std::ptrdiff_t>(qi), dist.end());
  const double max_r = dist[qi];
  if (!(max_r > 1e-9)) return {};
  const int l = params.rings, t = params.sectors, p = params.azimuths, q = params.elevations;
  std::vector<double> ring_r(static_cast<std::size_t>(l));
  for (int i = 0; i < l; ++i) ring_r[static_cast<std::size_t>(i)] = max_r * (i + 1) * (i + 1) / double(l * l);
  std::vector<double> ring_r2(ring_r.size());  // squared: points are binned by squared distance
  for (std::size_t i = 0; i < ring_r.size(); ++i) ring_r2[i] = ring_r[i] * ring_r[i];

  // 4. Signature of each plane = a row of A.
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(p * q, l * t);
  const double inv_n = 1.0 / static_cast<double>(n);
  const Eigen::Vector3d x_axis(1, 0, 0);  // the first PCA axis
  for (int ia = 0; ia < p; ++ia) {
    const double theta = M_PI * ia / p;
    for (int ie = 0; ie < q; ++ie) {
      const double phi = 0.5 * M_PI * ie / q;
      const Eigen::Vector3d m(std::cos(theta) * std::cos(phi), std::sin(theta) * std::cos(phi),
                              std::sin(phi));
      // In-plane axes: the projection of the first PCA axis, and m x that.
      Eigen::Vector3d u = x_axis - x_axis.dot(m) * m;
      if (u.norm() < 1e-9) u = Eigen::Vector3d(0, 1, 0) - m.y() * m;
      u.normalize();
      const Eigen::Vector3d v = m.cross(u);
      auto row = A.row(ia * q + ie);
      for (const auto& pt : pts) {
        const double a = pt.dot(u), b = pt.dot(v);
        const double rho2 = a * a + b * b;
        int ring = static_cast<int>(std::lower_bound(ring_r2.begin(), ring_r2.end(), rho2) - ring_r2.begin());
        ring = std::min(ring, l - 1);
        double ang = std::atan2(b, a);
        if (ang < 0) ang += 2 * M_PI;
        const int sector = std::min(t - 1, static_cast<int>(ang * t / (2 * M_PI)));
        row(ring * t + sector) += inv_n;
      }
    }
  }

  // 5. Descriptor = [u1; v1], the first singular pair of A, sign fixed by sum(v1) >= 0. u1 is the
  //    top eigenvector of A A^T (p q x p q, small), v1 = A^T u1 / sigma1: the same vectors as a
  //    full SVD at a fraction of its cost (only the first pair is used).
  const Eigen::MatrixXd AAt = A * A.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> top(AAt);
  Eigen::VectorXd u1 = top.eigenvectors().col(AAt.rows() - 1);  // eigenvalues ascending
  Eigen::VectorXd v1 = A.transpose() * u1;
  const double sigma1 = v1.norm();
  if (!(sigma1 > 1e-12)) return {};
  v1 /= sigma1;
  if (v1.sum() < 0) u1 = -u1, v1 = -v1;
  M2DPDescriptor d(u1.size() + v1.size());
  d << u1.cast<float>(), v1.cast<float>();
  return d;
}

float m2dpDistance(const M2DPDescriptor& a, const M2DPDescriptor& b) {
  if (a.size() == 0 || a.size() != b.size()) return std::numeric_limits<float>::infinity();
  return (a - b).norm();
}

}  // namespace radarslam
