#pragma once
// Conversions between a KeyframeMap (map/keyframe_map.h, exports in map/map_exports.h) and the
// map messages the map server publishes, and from received messages to the usual files
// (grid PNG/PGM + ROS map_server YAML, PCD, OctoMap .bt). Files are written atomically.
#include <filesystem>
#include <string>
#include <vector>

#include "radarslam/dds/messages.h"
#include "radarslam/map/keyframe_map.h"
#include "radarslam/map/map_exports.h"
#include "radarslam/map/map_layers.h"

namespace radarslam::dds {

/// Frame of everything the map server publishes.
inline constexpr const char* kMapFrame = "map";

/// nav_msgs/OccupancyGrid of buildOccupancy(map): cell = round(100 * P(occupied)), -1 where the
/// map never observed the cell, row 0 = lowest y, origin = grid corner.
OccupancyGridMsg gridMessage(const KeyframeMap& map, const GridExportParams& params, StampNs stamp);
OccupancyGridMsg gridMessage(const OccupancyRaster& raster, StampNs stamp);

/// sensor_msgs/PointCloud2 of every keyframe point in the map frame: fields x, y, z (= 0),
/// intensity (= power), FLOAT32, little-endian, point_step 16, height 1.
PointCloud2Msg cloudMessage(const KeyframeMap& map, StampNs stamp);
/// The fields of that layout (x, y, z, intensity at offsets 0, 4, 8, 12; FLOAT32, count 1).
const std::vector<PointFieldMsg>& cloudRecordFields();
/// A PointCloud2 of that layout holding `records` (kCloudRecordBytes each, map/layer_files.h):
/// every cloud message (whole map, from the layer file, one tile) is built here.
PointCloud2Msg cloudRecordsMessage(const HeaderMsg& header, std::vector<std::uint8_t> records);

/// octomap_msgs/Octomap (binary) of exportOctomap(map): data = OcTree::writeBinaryData.
OctomapMsg octomapMessage(const KeyframeMap& map, const OctomapExportParams& params, StampNs stamp);
/// The same for the grid_columns fill, from an occupancy raster already built (at the OctoMap's
/// resolution): the map server builds the raster once for the grid and the OctoMap.
OctomapMsg octomapMessage(const OccupancyRaster& raster, StampNs stamp);

/// The messages of a map's precomputed layers (map/layer_files.h: `map_dir`/layers/, described
/// by the manifest's `layers` section): each file is read once, checked (size, SHA-256, header)
/// and its body becomes the payload. Equal to the messages built from the keyframes with the
/// same parameters. Throws InputError naming the file.
OccupancyGridMsg gridMessage(const std::filesystem::path& map_dir, const MapLayersManifest& layers,
                             StampNs stamp);
PointCloud2Msg cloudMessage(const std::filesystem::path& map_dir, const MapLayersManifest& layers,
                            StampNs stamp);
OctomapMsg octomapMessage(const std::filesystem::path& map_dir, const MapLayersManifest& layers,
                          StampNs stamp);

/// SHA-256 (64 hex) of the grid cells (the int8 bytes of OccupancyGridMsg::data).
std::string gridSha256(const OccupancyGridMsg& grid);

/// Writes STEM.pgm, STEM.png (pixel = 255 * P(free), 205 for unknown cells, top row = highest y)
/// and STEM.yaml (ROS map_server: image STEM.pgm, resolution, origin, negate 0, thresholds,
/// mode scale) into `dir`. Throws InputError if the message is inconsistent (size != w*h).
std::vector<std::filesystem::path> writeGridFiles(const OccupancyGridMsg& grid,
                                                  const std::filesystem::path& dir,
                                                  const std::string& stem = "grid");

/// Writes a PCD v0.7 (DATA binary) with the message's FLOAT32 fields. Throws InputError if the
/// message is inconsistent or has a field that is not FLOAT32 with count 1.
void writePcdFile(const PointCloud2Msg& cloud, const std::filesystem::path& path);

/// Writes an OctoMap .bt file (readable by octovis / octomap::OcTree::readBinary). Throws
/// InputError if the message is not a binary OcTree or its data does not parse.
void writeOctomapFile(const OctomapMsg& octomap, const std::filesystem::path& path);

}  // namespace radarslam::dds
