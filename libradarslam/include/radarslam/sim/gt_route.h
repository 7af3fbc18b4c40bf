#pragma once
// A route from a real drive: the relative poses of an Oxford gt/radar_odometry.csv chained into an
// absolute trajectory, driven with its real timing (poses interpolated in time, stops and all),
// and the real scan start times (the scans' file names) for the simulated scans.
#include <filesystem>
#include <vector>

#include "radarslam/sim/road.h"
#include "radarslam/sim/route.h"

namespace radarslam::sim {

struct GroundTruthRoute {
  Route route;
  std::vector<StampNs> scan_starts;  ///< first-azimuth time of every scan (the file's 8866 for Oxford)
  std::vector<RoadPiece> roads;      ///< the chained trajectory as the road centreline
};

/// Reads and chains `csv` (errors name the file and line). Traversal 2 is the same drive
/// `traversal2_delay_s` later. `piece_m` is the road pieces' length, `half_width_m` their width.
GroundTruthRoute routeFromOxfordGroundTruth(const std::filesystem::path& csv, const RouteParams& params,
                                            int traversal, double half_width_m, double piece_m = 4.0);

}  // namespace radarslam::sim
