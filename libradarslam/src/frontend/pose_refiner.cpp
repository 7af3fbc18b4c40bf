#include "radarslam/frontend/pose_refiner.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace radarslam {

namespace {
/// Information matrix of a match, scaled so that a purely radial residual keeps its metres.
Eigen::Matrix2d information(const Correspondence& m, const RefineParams& p) {
  if (!(p.azimuth_sigma_rad > 0)) return Eigen::Matrix2d::Identity();
  const double r = m.ref.norm();
  if (r < 1e-6) return Eigen::Matrix2d::Identity();
  const Eigen::Vector2d u = m.ref / r;  // along the beam
  const Eigen::Vector2d t(-u.y(), u.x());
  const double st = std::max(r * p.azimuth_sigma_rad, p.range_sigma_m);
  const double ratio = (p.range_sigma_m * p.range_sigma_m) / (st * st);
  return u * u.transpose() + ratio * t * t.transpose();
}

/// The prior's information (times sigma^2, the data term's unit) and residual at a pose.
struct WeighedPrior {
  const PosePrior* prior = nullptr;
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();  ///< Sigma_pred^-1

  /// D = mean^-1 (+) T: the translation turned into the mean's frame, the heading difference.
  Eigen::Vector3d deviation(double x, double y, double th) const {
    const double c = std::cos(prior->mean.phi), s = std::sin(prior->mean.phi);
    const double dx = x - prior->mean.x, dy = y - prior->mean.y;
    return {c * dx + s * dy, -s * dx + c * dy, std::remainder(th - prior->mean.phi, 2 * M_PI)};
  }
  Eigen::Matrix3d jacobian() const {  // dD/d(x, y, th)
    const double c = std::cos(prior->mean.phi), s = std::sin(prior->mean.phi);
    Eigen::Matrix3d j = Eigen::Matrix3d::Identity();
    j.topLeftCorner<2, 2>() << c, s, -s, c;
    return j;
  }
};

struct Solution {
  double x, y, th;
  int iterations = 0;
  double data_cost = 0.0;  ///< sum of the robust costs rho(e_i) (m^2)
  double dof_sum = 0.0;    ///< sum of the Huber-weighted squared residuals (m^2)
};

/// Iteratively re-weighted Gauss-Newton from (x, y, th); `sigma2` scales the prior (0: none).
/// `costs`: also evaluate data_cost and dof_sum at the solution (one more pass over the matches,
/// needed only when a prior is weighed).
Solution solve(const Correspondences& matches, Solution s, const RefineParams& params,
               std::span<const Eigen::Matrix2d> shapes, const WeighedPrior& prior, double sigma2,
               bool costs) {
  const bool shaped = shapes.size() == matches.size();
  auto accumulate = [&](Eigen::Matrix3d* H, Eigen::Vector3d* b) {
    const double c = std::cos(s.th), sn = std::sin(s.th);
    s.data_cost = s.dof_sum = 0.0;
    for (std::size_t i = 0; i < matches.size(); ++i) {
      const Correspondence& m = matches[i];
      const double px = m.cur.x(), py = m.cur.y();
      const Eigen::Vector2d r(m.ref.x() - (c * px - sn * py + s.x), m.ref.y() - (sn * px + c * py + s.y));
      const Eigen::Matrix2d W = shaped ? shapes[i] : information(m, params);
      const double e = std::sqrt(r.dot(W * r));
      const double huber = e <= params.huber_m ? 1.0 : params.huber_m / e;
      const double w = m.weight * huber;
      s.data_cost += m.weight * (e <= params.huber_m ? e * e : params.huber_m * (2 * e - params.huber_m));
      s.dof_sum += w * e * e;
      if (!H) continue;
      // d(T (+) p)/d(x, y, th)
      Eigen::Matrix<double, 2, 3> J;
      J << 1, 0, -sn * px - c * py, 0, 1, c * px - sn * py;
      *H += w * J.transpose() * W * J;
      *b += w * J.transpose() * W * r;
    }
  };
  for (int it = 0; it < params.iterations; ++it) {
    Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
    Eigen::Vector3d b = Eigen::Vector3d::Zero();
    accumulate(&H, &b);
    if (prior.prior && sigma2 > 0) {
      const Eigen::Matrix3d Jp = prior.jacobian();
      const Eigen::Matrix3d L = sigma2 * prior.information;
      H += Jp.transpose() * L * Jp;
      b -= Jp.transpose() * L * prior.deviation(s.x, s.y, s.th);
    }
    const Eigen::Vector3d delta = H.ldlt().solve(b);
    if (!delta.allFinite()) break;
    s.x += delta.x();
    s.y += delta.y();
    s.th += delta.z();
    s.iterations = it + 1;
    if (delta.head<2>().norm() < 1e-6 && std::abs(delta.z()) < 1e-8) break;
  }
  if (costs) accumulate(nullptr, nullptr);  // the costs at the solution
  return s;
}
}  // namespace

RefineResult refinePose(const Correspondences& matches, const mrpt::math::TPose2D& initial,
                        const RefineParams& params, std::span<const Eigen::Matrix2d> shapes,
                        const PosePrior* prior) {
  RefineResult out;
  out.pose = initial;
  if (matches.size() < 2) return out;
  WeighedPrior weighed;
  if (prior && prior->covariance.allFinite()) {
    const Eigen::LLT<Eigen::Matrix3d> llt(0.5 * (prior->covariance + prior->covariance.transpose()));
    if (llt.info() == Eigen::Success) {  // not positive definite: no prior
      weighed.prior = prior;
      weighed.information = llt.solve(Eigen::Matrix3d::Identity());
    }
  }
  Solution s =
      solve(matches, {initial.x, initial.y, initial.phi}, params, shapes, {}, 0.0, weighed.prior != nullptr);
  if (weighed.prior) {
    // The matches' residual variance per degree of freedom (2 per match, 3 taken by the pose): the
    // unit in which the data term above is the log-likelihood times sigma^2.
    const double dof = 2.0 * static_cast<double>(matches.size()) - 3.0;
    const double sigma2 = dof > 0 ? s.dof_sum / dof : 0.0;
    if (sigma2 > 0) {
      const Solution with = solve(matches, s, params, shapes, weighed, sigma2, true);
      // The innovation test: adding the prior raises the minimum of the normalised cost by
      // d^T (Sigma_pred + Sigma_data)^-1 d (d: the data's estimate minus the prediction), which is
      // chi^2(3) distributed when both are right. A larger rise: the motion left the model (a hard
      // brake, a jolt) or the matches are wrong; either way the prior is not applied and the data's
      // estimate goes on to the odometry's plausibility checks.
      const Eigen::Vector3d d = weighed.deviation(with.x, with.y, with.th);
      const double rise = (with.data_cost - s.data_cost) / sigma2 + d.dot(weighed.information * d);
      out.prior_chi2 = rise;
      if (rise <= params.motion_prior_chi2) {
        s.x = with.x;
        s.y = with.y;
        s.th = with.th;
        s.iterations += with.iterations;
        out.prior_applied = true;
      }
    }
  }
  out.iterations = s.iterations;
  out.pose = mrpt::math::TPose2D(s.x, s.y, std::remainder(s.th, 2.0 * M_PI));
  const double c = std::cos(s.th), sn = std::sin(s.th);
  double sw = 0, se = 0;
  for (const auto& m : matches) {
    const Eigen::Vector2d r(m.ref.x() - (c * m.cur.x() - sn * m.cur.y() + s.x),
                            m.ref.y() - (sn * m.cur.x() + c * m.cur.y() + s.y));
    sw += m.weight;
    se += m.weight * r.squaredNorm();
  }
  out.rms_m = sw > 0 ? std::sqrt(se / sw) : 0.0;
  return out;
}

}  // namespace radarslam
