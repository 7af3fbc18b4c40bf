// MulRan global_pose.csv (FORMATS.md 2.4).
#include <mrpt/math/CMatrixFixed.h>
#include <mrpt/math/geometry.h>

#include <cmath>
#include <numbers>
#include <string>

#include "radarslam/core/errors.h"
#include "radarslam/io/ground_truth.h"
#include "text_util.h"

namespace radarslam {

using namespace io_detail;

mrpt::poses::CPose3D mulranBaseToRadar() {
  return mrpt::poses::CPose3D(1.50, -0.04, 1.97, 0.9 * std::numbers::pi / 180.0, 0.0, 0.0);
}

Trajectory readMulRanGroundTruth(const std::filesystem::path& csv,
                                 const mrpt::poses::CPose3D& base_to_radar) {
  auto in = openText(csv, "MulRan ground truth (global_pose.csv)");
  Trajectory traj;
  mrpt::poses::CPose3D first_inv;
  forEachDataLine(in, csv, ',', 0, [&](const DataLine& d) {
    const std::string& where = d.where;
    const auto& f = d.fields;
    if (f.size() != 13)
      throw InputError(where, "malformed row: expected 13 comma-separated fields (t_ns + 3x4 [R|t]), got " +
                                  std::to_string(f.size()));
    const StampNs t = parseStamp(f[0], where, "timestamp");
    mrpt::math::CMatrixDouble33 R;
    mrpt::math::CVectorFixedDouble<3> xyz;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) R(r, c) = parseDouble(f[1 + 4 * r + c], where, "rotation entry");
      xyz[r] = parseDouble(f[1 + 4 * r + 3], where, "translation entry");
    }
    if (std::abs(R.det() - 1.0) > 1e-3) throw InputError(where, "the 3x3 block is not a rotation matrix");
    const mrpt::poses::CPose3D world_radar = mrpt::poses::CPose3D(R, xyz) + base_to_radar;
    if (traj.empty())
      first_inv = -world_radar;
    else if (t <= traj.back().stamp)
      throw InputError(where, "timestamp is not after the previous row's");
    traj.push_back({t, projectSensorPoseToSE2(first_inv + world_radar)});
  });
  if (traj.empty()) throw InputError(csv.string(), "no ground-truth rows");
  checkPlausiblePoses(traj, csv.string());
  return traj;
}

}  // namespace radarslam
