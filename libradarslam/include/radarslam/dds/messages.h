#pragma once
// C++ value types of the DDS messages in share/idl (ROS 2 wire-compatible: builtin_interfaces,
// std_msgs, geometry_msgs, nav_msgs, sensor_msgs, octomap_msgs; plus radarslam/msg). They mirror
// the IDL field by field; dds/domain.h converts them to and from the idlc-generated C types, so
// no other code includes Cyclone DDS headers.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "radarslam/core/time.h"

namespace radarslam::dds {

/// DDS topic names. ROS 2 prefixes topics with "rt": ROS topic /map is DDS topic rt/map.
inline constexpr const char* kMapTopic = "rt/map";
inline constexpr const char* kCloudMapTopic = "rt/radarslam/cloud_map";
inline constexpr const char* kOctomapTopic = "rt/radarslam/octomap";
inline constexpr const char* kMapInfoTopic = "rt/radarslam/map_info";
inline constexpr const char* kMapFilesTopic = "rt/radarslam/map_files";
inline constexpr const char* kMapTilesTopic = "rt/radarslam/map_tiles";
inline constexpr const char* kCloudMapTilesTopic = "rt/radarslam/cloud_map_tiles";
inline constexpr const char* kPoseTopic = "rt/radarslam/pose";
inline constexpr const char* kLocalizationStatusTopic = "rt/radarslam/localization_status";
inline constexpr const char* kRadarScanTopic = "rt/radarslam/radar_scan";

/// builtin_interfaces/Time.
struct TimeMsg {
  std::int32_t sec = 0;
  std::uint32_t nanosec = 0;
  bool operator==(const TimeMsg&) const = default;
};
TimeMsg toTimeMsg(StampNs t);
StampNs fromTimeMsg(const TimeMsg& t);

/// std_msgs/Header.
struct HeaderMsg {
  TimeMsg stamp;
  std::string frame_id;
  bool operator==(const HeaderMsg&) const = default;
};

/// geometry_msgs/Pose (position + orientation quaternion).
struct PoseMsg {
  double x = 0, y = 0, z = 0;
  double qx = 0, qy = 0, qz = 0, qw = 1;
  bool operator==(const PoseMsg&) const = default;
};

/// nav_msgs/OccupancyGrid (with MapMetaData flattened into the fields below).
struct OccupancyGridMsg {
  HeaderMsg header;
  TimeMsg map_load_time;
  float resolution = 0.f;  ///< m per cell
  std::uint32_t width = 0, height = 0;
  PoseMsg origin;                 ///< corner of cell (0,0) in the map frame
  std::vector<std::int8_t> data;  ///< row-major, row 0 = lowest y; 0..100 P(occupied) %, -1 unknown
  bool operator==(const OccupancyGridMsg&) const = default;
};

/// sensor_msgs/PointField; datatype values as in ROS (FLOAT32 = 7).
struct PointFieldMsg {
  static constexpr std::uint8_t kFloat32 = 7;
  std::string name;
  std::uint32_t offset = 0;
  std::uint8_t datatype = kFloat32;
  std::uint32_t count = 1;
  bool operator==(const PointFieldMsg&) const = default;
};

/// sensor_msgs/PointCloud2.
struct PointCloud2Msg {
  HeaderMsg header;
  std::uint32_t height = 1, width = 0;
  std::vector<PointFieldMsg> fields;
  bool is_bigendian = false;
  std::uint32_t point_step = 0, row_step = 0;
  std::vector<std::uint8_t> data;
  bool is_dense = true;
  bool operator==(const PointCloud2Msg&) const = default;
};

/// octomap_msgs/Octomap (binary = true: data is OcTree::writeBinaryData, i.e. a .bt file's body).
struct OctomapMsg {
  HeaderMsg header;
  bool binary = true;
  std::string id = "OcTree";
  double resolution = 0;
  std::vector<std::int8_t> data;
  bool operator==(const OctomapMsg&) const = default;
};

/// geometry_msgs/PoseWithCovarianceStamped.
struct PoseWithCovarianceStampedMsg {
  HeaderMsg header;
  PoseMsg pose;
  std::array<double, 36> covariance{};  ///< row-major 6x6 over (x, y, z, rot x, rot y, rot z)
  bool operator==(const PoseWithCovarianceStampedMsg&) const = default;
};

/// radarslam/MapInfo: which map the server publishes; grid_sha256 ties it to the rt/map grid (or,
/// for a tiled grid, to the grid its tiles make up; docs/dds.md, "Tiled grids").
struct MapInfoMsg {
  HeaderMsg header;
  std::string map_name;
  std::uint32_t format_version = 0;
  std::uint32_t keyframes = 0;
  std::uint32_t revision = 0;   ///< increments on every (re)load by the server
  std::string grid_sha256;      ///< SHA-256 (hex) of the full grid's cells (OccupancyGridMsg::data)
  std::string manifest_sha256;  ///< SHA-256 (hex) of the map's manifest.yaml
  TimeMsg created;              ///< map creation time
  std::uint32_t grid_width = 0, grid_height = 0;  ///< the full-resolution grid [cells]
  std::uint32_t tile_cells = 0;  ///< > 0: rt/map is an overview, the grid comes as MapTileMsg
  std::uint32_t tiles_x = 0, tiles_y = 0;
  std::vector<std::uint32_t> tile_indices;  ///< tile_y * tiles_x + tile_x of each tile sent, ascending
  std::vector<std::uint8_t> tile_sha256;    ///< 32 bytes (binary SHA-256 of its cells) per tile
  std::string overview_sha256;              ///< SHA-256 (hex) of rt/map's cells when tiled
  /// > 0: the cloud comes as this many PointCloud2 tiles on rt/radarslam/cloud_map_tiles, in order
  std::uint32_t cloud_tile_count = 0;
  std::uint32_t cloud_points = 0;  ///< points of all cloud tiles
  std::string cloud_sha256;        ///< SHA-256 (hex) of the cloud tiles' data, concatenated in order
  bool operator==(const MapInfoMsg&) const = default;
};

/// radarslam/MapTile: one tile of a tiled grid (rt/radarslam/map_tiles).
struct MapTileMsg {
  HeaderMsg header;  ///< = MapInfo.header of the publication
  std::uint32_t revision = 0;
  std::uint32_t tile_x = 0, tile_y = 0, tile_cells = 0, tile_count = 0;
  std::string cells_sha256;  ///< SHA-256 (hex) of grid.data
  OccupancyGridMsg grid;     ///< the tile as a grid; origin = the tile's corner
  bool operator==(const MapTileMsg&) const = default;
};

/// radarslam/MapFileChunk: one piece of one file of a map directory (rt/radarslam/map_files;
/// dds/map_file_publisher.h sends them, dds/map_file_assembler.h checks and reassembles them).
struct MapFileChunkMsg {
  HeaderMsg header;                ///< stamp = the publication's (= MapInfo's), frame_id "map"
  std::string map_name;            ///< = MapInfo.map_name
  std::uint32_t revision = 0;      ///< = MapInfo.revision
  std::string manifest_sha256;     ///< SHA-256 (hex) of the manifest.yaml sent
  std::uint32_t file_count = 0;    ///< files of the publication, manifest.yaml included
  std::uint32_t total_chunks = 0;  ///< chunks of all files of the publication
  std::uint32_t file_index = 0;    ///< 0..file_count-1 (manifest.yaml = 0)
  std::string path;                ///< relative to the map directory
  std::uint64_t file_size = 0;
  std::string file_sha256;  ///< SHA-256 (hex) of the whole file
  std::uint32_t chunk_index = 0, chunk_count = 0;
  std::uint64_t offset = 0;  ///< of `data` in the file
  std::vector<std::uint8_t> data;
  bool operator==(const MapFileChunkMsg&) const = default;
};

/// radarslam/LocalizationStatus: the localiser's integrity status of one scan.
struct LocalizationStatusMsg {
  HeaderMsg header;        ///< stamp = the scan's reference time, frame_id = "map"
  std::uint8_t level = 2;  ///< 0 OK (global_fix, tracking), 1 WARN (degraded), 2 ERROR (lost)
  std::string status;      ///< global_fix | tracking | degraded | lost
  std::string check;       ///< failed integrity check, "" if none
  bool pose_published = false;
  std::int32_t keyframe = -1;
  double fit_score = 0;
  std::uint32_t inliers = 0;
  double sigma_xy_m = 0, sigma_yaw_rad = 0;
  std::uint32_t global_fixes = 0;
  bool operator==(const LocalizationStatusMsg&) const = default;
};

/// radarslam/RadarScan: one polar sweep (see CObservationRadarScan and dds/scan_messages.h).
struct RadarScanMsg {
  HeaderMsg header;  ///< stamp = reference time, frame_id = sensor frame
  std::uint32_t num_azimuths = 0, num_bins = 0;
  double range_resolution = 0, range_offset = 0;
  std::vector<std::int64_t> azimuth_stamps_ns;
  std::vector<double> azimuth_angles;
  std::vector<std::uint8_t> azimuth_valid;
  std::vector<std::uint8_t> power;
  bool operator==(const RadarScanMsg&) const = default;
};

}  // namespace radarslam::dds
