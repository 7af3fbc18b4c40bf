// Boreas applanix/radar_poses.csv (FORMATS.md 3.2).
#include <mrpt/math/CMatrixFixed.h>
#include <Eigen/Dense>

#include <cmath>
#include <string>

#include "radarslam/core/errors.h"
#include "radarslam/io/ground_truth.h"
#include "text_util.h"

namespace radarslam {

using namespace io_detail;

namespace {
// pyboreas utils.py: the passive (UTIAS) elementary rotations.
mrpt::math::CMatrixDouble33 passiveRoll(double r) {
  mrpt::math::CMatrixDouble33 m;
  m(0, 0) = 1, m(0, 1) = 0, m(0, 2) = 0;
  m(1, 0) = 0, m(1, 1) = std::cos(r), m(1, 2) = std::sin(r);
  m(2, 0) = 0, m(2, 1) = -std::sin(r), m(2, 2) = std::cos(r);
  return m;
}
mrpt::math::CMatrixDouble33 passivePitch(double p) {
  mrpt::math::CMatrixDouble33 m;
  m(0, 0) = std::cos(p), m(0, 1) = 0, m(0, 2) = -std::sin(p);
  m(1, 0) = 0, m(1, 1) = 1, m(1, 2) = 0;
  m(2, 0) = std::sin(p), m(2, 1) = 0, m(2, 2) = std::cos(p);
  return m;
}
mrpt::math::CMatrixDouble33 passiveYaw(double y) {
  mrpt::math::CMatrixDouble33 m;
  m(0, 0) = std::cos(y), m(0, 1) = std::sin(y), m(0, 2) = 0;
  m(1, 0) = -std::sin(y), m(1, 1) = std::cos(y), m(1, 2) = 0;
  m(2, 0) = 0, m(2, 1) = 0, m(2, 2) = 1;
  return m;
}
}  // namespace

Trajectory readBoreasGroundTruth(const std::filesystem::path& csv) {
  auto in = openText(csv, "Boreas ground truth (applanix/radar_poses.csv)");
  std::string line;
  if (!std::getline(in, line)) throw InputError(csv.string(), "empty file (expected a CSV header)");
  const auto header = split(line, ',');
  if (header.size() != 13 || (header[0] != "GPSTime" && header[0] != "t"))
    throw InputError(csv.string(),
                     "unexpected header (expected 13 columns 'GPSTime,easting,northing,altitude,"
                     "vel_east,vel_north,vel_up,roll,pitch,heading,angvel_z,angvel_y,angvel_x')");
  Trajectory traj;
  forEachDataLine(in, csv, ',', 1, [&](const DataLine& d) {
    const std::string& where = d.where;
    const auto& f = d.fields;
    if (f.size() != 13)
      throw InputError(where,
                       "malformed row: expected 13 comma-separated fields, got " + std::to_string(f.size()));
    const StampNs t = parseStamp(f[0], where, "GPSTime");
    double v[13];
    for (int k = 1; k < 13; ++k) v[k] = parseDouble(f[k], where, "pose field");
    // pyboreas get_transform: C_enu_sensor = roll(r) @ pitch(p) @ yaw(y), translation (x, y, z).
    const mrpt::math::CMatrixDouble33 C(passiveRoll(v[7]).asEigen() * passivePitch(v[8]).asEigen() *
                                        passiveYaw(v[9]).asEigen());
    mrpt::math::CVectorFixedDouble<3> xyz;
    xyz[0] = v[1], xyz[1] = v[2], xyz[2] = v[3];
    const mrpt::poses::CPose3D pose(C, xyz);
    if (!traj.empty() && t <= traj.back().stamp)
      throw InputError(where, "timestamp " + std::string(f[0]) + " is not after the previous row's");
    traj.push_back({t, projectSensorPoseToSE2(pose)});
  });
  if (traj.empty()) throw InputError(csv.string(), "no ground-truth rows");
  checkPlausiblePoses(traj, csv.string());
  return traj;
}

}  // namespace radarslam
