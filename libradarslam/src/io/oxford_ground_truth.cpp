// Oxford Radar RobotCar gt/radar_odometry.csv (FORMATS.md 1.2).
#include <mrpt/math/TPose2D.h>

#include <string>

#include "radarslam/core/errors.h"
#include "radarslam/io/ground_truth.h"
#include "text_util.h"

namespace radarslam {

using namespace io_detail;

std::vector<OxfordOdometryRow> readOxfordOdometryRows(const std::filesystem::path& csv) {
  auto in = openText(csv, "Oxford ground truth (gt/radar_odometry.csv)");
  std::string line;
  if (!std::getline(in, line)) throw InputError(csv.string(), "empty file (expected a CSV header)");
  if (trim(line).rfind("source_timestamp,destination_timestamp,x,y,z,roll,pitch,yaw", 0) != 0)
    throw InputError(csv.string(),
                     "unexpected header (expected 'source_timestamp,destination_timestamp,x,y,z,"
                     "roll,pitch,yaw,source_radar_timestamp,destination_radar_timestamp')");
  std::vector<OxfordOdometryRow> rows;
  forEachDataLine(in, csv, ',', 1, [&](const DataLine& d) {
    const std::string& where = d.where;
    const auto& f = d.fields;
    if (f.size() != 10)
      throw InputError(where,
                       "malformed row: expected 10 comma-separated fields, got " + std::to_string(f.size()));
    OxfordOdometryRow r;
    r.line = d.number;
    r.source = parseMicroseconds(f[0], where, "source_timestamp");
    r.destination = parseMicroseconds(f[1], where, "destination_timestamp");
    r.motion = {parseDouble(f[2], where, "x"), parseDouble(f[3], where, "y"),
                parseDouble(f[7], where, "yaw")};
    for (int k : {4, 5, 6}) parseDouble(f[k], where, k == 4 ? "z" : (k == 5 ? "roll" : "pitch"));
    r.source_radar = parseMicroseconds(f[8], where, "source_radar_timestamp");
    r.destination_radar = parseMicroseconds(f[9], where, "destination_radar_timestamp");
    if (r.source <= r.destination)
      throw InputError(where, "source_timestamp must be later than destination_timestamp");
    rows.push_back(r);
  });
  if (rows.empty()) throw InputError(csv.string(), "no ground-truth rows");
  return rows;
}

Trajectory chainOxfordOdometry(const std::vector<OxfordOdometryRow>& rows, const std::filesystem::path& csv) {
  Trajectory traj;
  if (rows.empty()) return traj;
  traj.reserve(rows.size() + 1);
  traj.push_back({rows.front().destination, mrpt::math::TPose2D(0, 0, 0)});
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const auto& r = rows[k];
    if (r.destination != traj.back().stamp)
      throw InputError(lineWhere(csv, r.line ? r.line : k + 2),
                       "ground-truth gap: destination_timestamp " + std::to_string(r.destination / kNsPerUs) +
                           " != previous row's source_timestamp " +
                           std::to_string(traj.back().stamp / kNsPerUs));
    // T_abs(new) = T_abs(prev) * T_rel  (TPose2D::operator+ is SE(2) composition).
    traj.push_back({r.source, traj.back().pose + r.motion});
  }
  checkPlausiblePoses(traj, csv.string());
  return traj;
}

Trajectory readOxfordGroundTruth(const std::filesystem::path& csv) {
  return chainOxfordOdometry(readOxfordOdometryRows(csv), csv);
}

}  // namespace radarslam
