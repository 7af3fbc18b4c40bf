#pragma once
// The reusable map that SLAM fills and localisation, exports and other tools read: keyframes
// (pose in the map frame, the keyframe's peak point cloud in the sensor frame, a global
// descriptor), map points and the pose graph. Plain data; storage is map/map_io.h, exports are
// map/map_exports.h. Units: metres, radians, nanoseconds since the UNIX epoch.
#include <mrpt/math/TPose2D.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "radarslam/core/time.h"

namespace radarslam {

/// Scan geometry of the radar the map was built with (as in CObservationRadarScan).
struct MapSensorGeometry {
  std::uint32_t num_azimuths = 400;
  std::uint32_t num_bins = 3768;
  double range_resolution_m = 0.0438;
  double range_offset_m = 0.0;
  bool operator==(const MapSensorGeometry&) const = default;
};

struct MapMetadata {
  /// The version loadMap read; saveMap writes kMapFormatVersion (map_io.h), the default.
  std::uint32_t format_version = 2;
  MapSensorGeometry sensor;
  std::string parameters_yaml;   ///< the parameters the map was built with, as YAML text
  StampNs created_ns = 0;        ///< creation time (saveMap fills it in when 0)
  std::string source_dataset;    ///< e.g. the dataset directory the map was built from
  std::string software_version;  ///< radarslam version that built the map
  /// Keyframe clouds at their scan's reference time (motion compensated, as `radarslam map` writes
  /// them); false: raw sweeps, each point where the sensor was when it fired (`map-synth`), which a
  /// localiser compensates itself (reloc/map_motion.h). Manifests without the key: true.
  bool clouds_motion_compensated = true;
  bool operator==(const MapMetadata&) const = default;
};

/// One point of a keyframe's cloud, sensor frame (x, y, power as in radar/peak_cloud.h RadarPoint).
struct KeyframePoint {
  float x = 0.f, y = 0.f;
  float power = 0.f;  ///< 0..255
  bool operator==(const KeyframePoint&) const = default;
};

struct Keyframe {
  std::uint64_t id = 0;
  StampNs stamp_ns = 0;
  mrpt::math::TPose2D pose;           ///< sensor pose in the map frame
  std::vector<KeyframePoint> points;  ///< sensor frame
  std::vector<float> descriptor;      ///< global descriptor (M2DP); may be empty
  bool operator==(const Keyframe& o) const {
    return id == o.id && stamp_ns == o.stamp_ns && pose.x == o.pose.x && pose.y == o.pose.y &&
           pose.phi == o.pose.phi && points == o.points && descriptor == o.descriptor;
  }
};

struct MapPoint {
  std::uint64_t id = 0;
  double x = 0.0, y = 0.0;                 ///< map frame
  std::vector<std::uint64_t> observed_by;  ///< keyframe ids
  bool operator==(const MapPoint&) const = default;
};

enum class EdgeKind : std::uint8_t { Odometry = 0, Loop = 1 };

struct PoseGraphEdge {
  std::uint64_t from = 0, to = 0;       ///< keyframe ids
  mrpt::math::TPose2D relative;         ///< pose of `to` in the frame of `from`
  std::array<double, 9> information{};  ///< 3x3 row-major, order (x, y, phi)
  EdgeKind kind = EdgeKind::Odometry;
  bool operator==(const PoseGraphEdge& o) const {
    return from == o.from && to == o.to && relative.x == o.relative.x && relative.y == o.relative.y &&
           relative.phi == o.relative.phi && information == o.information && kind == o.kind;
  }
};

struct KeyframeMap {
  MapMetadata meta;
  std::vector<Keyframe> keyframes;
  std::vector<MapPoint> points;
  std::vector<PoseGraphEdge> edges;
  bool operator==(const KeyframeMap&) const = default;
};

}  // namespace radarslam
