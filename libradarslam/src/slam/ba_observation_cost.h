#pragma once
// The local bundle adjustment's observation residual (paper Sec. III-B) with analytic Jacobians;
// the module's internal, seen by its unit test (test_slam: gradient check against finite
// differences).
#include <ceres/sized_cost_function.h>
#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include <cmath>

namespace radarslam::slam_detail {

/// r = L (R(phi)^T (p - t) - z) / sigma, pose = (x, y, phi), point = (x, y), L^T L = the
/// observation's information shape (identity: isotropic), with its analytic Jacobians (the BA's
/// inner loop: about 3x cheaper than automatic differentiation's jets).
class ObservationCost final : public ceres::SizedCostFunction<2, 3, 2> {
 public:
  ObservationCost(const Eigen::Vector2d& z, double sigma,
                  const Eigen::Matrix2d& information = Eigen::Matrix2d::Identity())
      : z_(z), w_(1.0 / sigma) {
    if (!information.isIdentity()) {
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(0.5 * (information + information.transpose()));
      l_ = eig.eigenvalues().cwiseMax(0.0).cwiseSqrt().asDiagonal() * eig.eigenvectors().transpose();
      shaped_ = true;
    }
  }
  const Eigen::Vector2d& z() const { return z_; }
  bool Evaluate(double const* const* parameters, double* r, double** jacobians) const override {
    const double* pose = parameters[0];
    const double* point = parameters[1];
    const double c = std::cos(pose[2]), s = std::sin(pose[2]);
    const double dx = point[0] - pose[0], dy = point[1] - pose[1];
    const double lx = c * dx + s * dy, ly = -s * dx + c * dy;  // the point in the keyframe's frame
    r[0] = (lx - z_.x()) * w_;
    r[1] = (ly - z_.y()) * w_;
    if (shaped_) return evaluateShaped(r, jacobians, c, s, lx, ly);
    if (jacobians == nullptr) return true;
    if (jacobians[0] != nullptr) {  // d r / d(x, y, phi), row-major 2x3
      double* j = jacobians[0];
      j[0] = -c * w_, j[1] = -s * w_, j[2] = ly * w_;
      j[3] = s * w_, j[4] = -c * w_, j[5] = -lx * w_;
    }
    if (jacobians[1] != nullptr) {  // d r / d(px, py), row-major 2x2
      double* j = jacobians[1];
      j[0] = c * w_, j[1] = s * w_;
      j[2] = -s * w_, j[3] = c * w_;
    }
    return true;
  }

 private:
  /// r and the Jacobians above, each multiplied by L from the left.
  bool evaluateShaped(double* r, double** jacobians, double c, double s, double lx, double ly) const {
    const Eigen::Vector2d e = l_ * Eigen::Vector2d(r[0], r[1]);
    r[0] = e.x();
    r[1] = e.y();
    if (jacobians == nullptr) return true;
    if (jacobians[0] != nullptr) {
      Eigen::Matrix<double, 2, 3, Eigen::RowMajor> j;
      j << -c * w_, -s * w_, ly * w_, s * w_, -c * w_, -lx * w_;
      Eigen::Map<Eigen::Matrix<double, 2, 3, Eigen::RowMajor>> out(jacobians[0]);
      out = l_ * j;
    }
    if (jacobians[1] != nullptr) {
      Eigen::Matrix<double, 2, 2, Eigen::RowMajor> j;
      j << c * w_, s * w_, -s * w_, c * w_;
      Eigen::Map<Eigen::Matrix<double, 2, 2, Eigen::RowMajor>> out(jacobians[1]);
      out = l_ * j;
    }
    return true;
  }

  Eigen::Vector2d z_;
  double w_;
  Eigen::Matrix2d l_ = Eigen::Matrix2d::Identity();
  bool shaped_ = false;
};

}  // namespace radarslam::slam_detail
