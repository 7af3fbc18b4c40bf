#pragma once
// The simulated vehicle's route through a World: a tour of the street grid and the countryside
// loop with rounded corners, a speed profile (0-15 m/s, limited acceleration, slow in turns, stops
// at some intersections) and several loop closures, including revisits in the opposite direction.
// The radar's pose at any time is interpolated from the route (so each azimuth can be fired from
// its own pose: motion distortion).
#include <mrpt/math/TPose2D.h>

#include <cstdint>
#include <vector>

#include "radarslam/core/trajectory.h"
#include "radarslam/sim/road.h"
#include "radarslam/sim/world.h"

namespace radarslam::sim {

struct RouteParams {
  double lane_offset_m = 1.8;  ///< traversal 1: left of the street centreline (UK); valid [-20, 20]
  double lane_offset_traversal2_m = 0.6;  ///< traversal 2: a different lane position; valid [-20, 20]
  double city_speed_mps = 11.0;           ///< valid (0, 15]
  double corridor_speed_mps = 13.0;       ///< valid (0, 15]
  double country_speed_mps = 15.0;        ///< never above 15 m/s; valid (0, 15]
  double lateral_accel_mps2 = 2.0;        ///< sets the speed in turns; valid (0, 20]
  /// Length over which the curvature ramps into and out of each turn (the centreline is averaged
  /// over this window: a clothoid-like ramp instead of the fillets' curvature step); 0 = steps.
  /// The yaw acceleration of a turn entered at the lateral-acceleration limit is about
  /// lateral_accel_mps2 / this (2 / 10 = 11.5 deg/s^2). Valid [0, 50].
  double curvature_transition_m = 10.0;  ///< curvature ramp into and out of turns; 0 = steps
  /// Yaw-rate and yaw-acceleration limits of the speed profile (a driver slows down for tight
  /// corners); real Oxford ground truth 2019-01-10: yaw rate p99 24.7 deg/s, max 33.6; yaw
  /// acceleration p99 15.3 deg/s^2 (docs/simulator.md). Valid (0, 180] and (0, 1000].
  double max_yaw_rate_dps = 30.0;             ///< slows tight corners
  double max_yaw_accel_dps2 = 15.0;           ///< slows where the curvature ramps
  double accel_mps2 = 1.5, decel_mps2 = 2.5;  ///< valid accel_mps2 (0, 20], decel_mps2 (0, 20]
  double stop_probability = 0.35;             ///< per straight crossing of an intersection; valid [0, 1]
  double stop_min_s = 2.0, stop_max_s = 6.0;  ///< valid stop_min_s [0, 600], stop_max_s [0, 600]
  double corner_radius_m = 9.0;               ///< valid [1, 100]
  double country_corner_radius_m = 45.0;      ///< valid [1, 1000]
  double start_time_s = 1600000000.0;  ///< UNIX time of the route start (traversal 1); valid [0, 4000000000]
  double traversal2_delay_s = 7 * 86400.0;  ///< traversal 2 starts this much later; valid [0, 1000000000]
};

struct RouteSample {
  double s = 0;         ///< arc length, m
  double t_arrive = 0;  ///< seconds since the route start
  double t_depart = 0;  ///< > t_arrive while stopped here
  double x = 0, y = 0, yaw = 0;
  double speed = 0;
};

class Route {
 public:
  std::vector<RouteSample> samples;
  StampNs start_stamp = 0;
  int traversal = 1;

  double length() const { return samples.empty() ? 0.0 : samples.back().s; }
  double duration() const { return samples.empty() ? 0.0 : samples.back().t_depart; }
  /// Radar pose at time t (UNIX ns), clamped to the route's time span.
  mrpt::math::TPose2D poseAt(StampNs t) const;
  double speedAt(StampNs t) const;
  /// Time (UNIX ns) at which the route reaches arc length s.
  StampNs stampAtDistance(double s) const;
};

/// A vertex of a tour: the route goes straight from vertex to vertex, with a circular fillet of
/// `radius` at each corner, at most `speed_in` on the leg arriving here, and maybe a stop before
/// an intersection crossed straight (RouteParams::stop_probability).
struct RouteWaypoint {
  Vec2 p;
  double radius = 9;
  double speed_in = 11;
  bool intersection = false;
  double half_width = 6;  ///< of the road on the leg arriving here (route worlds)
};

/// The route along laps of `lap` (which must end where it starts for laps to chain) until it is
/// at least `min_length_m` long and lasts at least `min_duration_s`; speed profile from `params`
/// (limits, lateral acceleration in turns, acceleration, stops), lane offset per traversal.
Route planRouteThrough(const std::vector<RouteWaypoint>& lap, const RouteParams& params, std::uint64_t seed,
                       int traversal, double min_length_m = 0, double min_duration_s = 0);

/// The road centreline of one lap (the same fillets as the route, no lane offset), as pieces of
/// at most `max_piece_m` carrying the half-width of their leg.
std::vector<RoadPiece> roadCentreline(const std::vector<RouteWaypoint>& lap, const RouteParams& params,
                                      double max_piece_m = 4.0);

/// The route for traversal 1 or 2 of `world`: laps of the tour until it is at least
/// `min_length_m` long and lasts at least `min_duration_s` (then it ends with a stop).
Route planRoute(const World& world, const RouteParams& params, std::uint64_t seed, int traversal,
                double min_length_m = 0, double min_duration_s = 0);

/// A place where the trajectory comes back to where it was at least `min_gap_s` earlier.
struct LoopEvent {
  std::size_t later = 0, earlier = 0;  ///< indices into the trajectory
  double distance_m = 0;
  bool opposite_direction = false;  ///< headings differ by more than 120 degrees
};

/// Loop closures in a trajectory: contiguous revisits (within `radius_m`) are one event.
std::vector<LoopEvent> findLoops(const Trajectory& traj, double radius_m = 8.0, double min_gap_s = 30.0);

}  // namespace radarslam::sim
