#include "map_validation.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <unordered_set>

#include "radarslam/core/errors.h"

namespace radarslam::mapcodec {

namespace {

// Geometry of any radar we read (CObservationRadarScan's sanity limits; RAS6 has 6848 bins).
constexpr std::uint32_t kMaxAzimuths = 1u << 14;
constexpr std::uint32_t kMaxBins = 1u << 16;
constexpr double kMaxRangeResolutionM = 10.0;
constexpr double kMaxRangeOffsetM = 1000.0;

std::string num(double v) {
  if (std::isnan(v)) return "NaN";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// "<value> is NaN" / "is inf" / "is 1e300, beyond +-bound" or "" if fine.
std::string badValue(double v, double bound) {
  if (!std::isfinite(v)) return "is " + num(v);
  if (std::abs(v) > bound) return "is " + num(v) + ", beyond +-" + num(bound);
  return "";
}

// Throws "<what>: <field> is NaN" etc.
void check(const std::string& file, const std::string& what, const std::string& field, double v,
           double bound) {
  if (const std::string why = badValue(v, bound); !why.empty())
    throw InputError(file, what + ": " + field + " " + why);
}

void checkPose(const std::string& file, const std::string& what, const char* name,
               const mrpt::math::TPose2D& p) {
  check(file, what, std::string(name) + " x", p.x, kMaxCoordinateM);
  check(file, what, std::string(name) + " y", p.y, kMaxCoordinateM);
  check(file, what, std::string(name) + " phi", p.phi, kMaxAngleRad);
}

std::unordered_set<std::uint64_t> keyframeIds(const KeyframeMap& map) {
  std::unordered_set<std::uint64_t> ids;
  for (const auto& kf : map.keyframes) ids.insert(kf.id);
  return ids;
}

void checkInformation(const std::string& file, const std::string& what, const std::array<double, 9>& m) {
  double scale = 0.0;
  for (std::size_t i = 0; i < 9; ++i) {
    if (!std::isfinite(m[i]))
      throw InputError(file, what + ": information matrix entry " + std::to_string(i) + " is " + num(m[i]));
    scale = std::max(scale, std::abs(m[i]));
  }
  const double tol = 1e-9 * std::max(scale, 1.0);
  for (int r = 0; r < 3; ++r)
    for (int c = r + 1; c < 3; ++c)
      if (std::abs(m[3 * r + c] - m[3 * c + r]) > tol)
        throw InputError(file, what + ": information matrix is not symmetric");
  Eigen::Matrix3d a;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) a(r, c) = m[3 * r + c];
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(a, Eigen::EigenvaluesOnly);
  if (eig.eigenvalues().minCoeff() < -tol)
    throw InputError(file, what + ": information matrix is not positive semi-definite (eigenvalue " +
                               num(eig.eigenvalues().minCoeff()) + ")");
}

}  // namespace

void validateSensor(const MapSensorGeometry& s, const std::string& file) {
  if (s.num_azimuths == 0 || s.num_azimuths > kMaxAzimuths)
    throw InputError(file, "sensor.num_azimuths must be 1.." + std::to_string(kMaxAzimuths) + " (got " +
                               std::to_string(s.num_azimuths) + ")");
  if (s.num_bins == 0 || s.num_bins > kMaxBins)
    throw InputError(file, "sensor.num_bins must be 1.." + std::to_string(kMaxBins) + " (got " +
                               std::to_string(s.num_bins) + ")");
  if (!(s.range_resolution_m > 0.0 && s.range_resolution_m <= kMaxRangeResolutionM))
    throw InputError(file, "sensor.range_resolution_m must be > 0 and <= " + num(kMaxRangeResolutionM) +
                               " (got " + num(s.range_resolution_m) + ")");
  check(file, "sensor", "range_offset_m", s.range_offset_m, kMaxRangeOffsetM);
}

void validateKeyframes(const KeyframeMap& map, const std::string& file) {
  std::unordered_set<std::uint64_t> ids;
  for (const auto& kf : map.keyframes) {
    const std::string what = "keyframe " + std::to_string(kf.id);
    if (!ids.insert(kf.id).second) throw InputError(file, what + ": duplicate keyframe id");
    checkPose(file, what, "pose", kf.pose);
    for (std::size_t i = 0; i < kf.points.size(); ++i) {
      const auto& p = kf.points[i];
      const std::string pw = "point " + std::to_string(i);
      check(file, what, pw + " x", p.x, kMaxSensorRangeM);
      check(file, what, pw + " y", p.y, kMaxSensorRangeM);
      if (!std::isfinite(p.power)) throw InputError(file, what + ": " + pw + " power is " + num(p.power));
    }
    for (std::size_t i = 0; i < kf.descriptor.size(); ++i)
      if (!std::isfinite(kf.descriptor[i]))
        throw InputError(file,
                         what + ": descriptor value " + std::to_string(i) + " is " + num(kf.descriptor[i]));
  }
}

void validatePoints(const KeyframeMap& map, const std::string& file) {
  const auto ids = keyframeIds(map);
  std::unordered_set<std::uint64_t> point_ids;
  for (const auto& p : map.points) {
    const std::string what = "map point " + std::to_string(p.id);
    if (!point_ids.insert(p.id).second) throw InputError(file, what + ": duplicate map point id");
    check(file, what, "x", p.x, kMaxCoordinateM);
    check(file, what, "y", p.y, kMaxCoordinateM);
    for (const auto k : p.observed_by)
      if (!ids.count(k))
        throw InputError(file,
                         what + ": observed by keyframe " + std::to_string(k) + ", which does not exist");
  }
}

void validateGraph(const KeyframeMap& map, const std::string& file) {
  const auto ids = keyframeIds(map);
  for (std::size_t i = 0; i < map.edges.size(); ++i) {
    const auto& e = map.edges[i];
    const std::string what =
        "edge " + std::to_string(i) + " (" + std::to_string(e.from) + " -> " + std::to_string(e.to) + ")";
    for (const auto k : {e.from, e.to})
      if (!ids.count(k))
        throw InputError(file,
                         what + ": references keyframe " + std::to_string(k) + ", which does not exist");
    if (e.from == e.to) throw InputError(file, what + ": connects a keyframe to itself");
    checkPose(file, what, "relative pose", e.relative);
    checkInformation(file, what, e.information);
  }
}

}  // namespace radarslam::mapcodec
