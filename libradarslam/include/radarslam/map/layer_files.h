#pragma once
// The file formats of a map's precomputed layers (map/map_layers.h): encoders used when saving,
// and checked readers used by the map server. Every reader verifies the file's size and SHA-256
// against its manifest entry and parses only the header; the body is read once, straight into
// the caller's buffer (the message payload). Errors are InputError naming the file.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "radarslam/map/cloud_tiles.h"
#include "radarslam/map/keyframe_map.h"
#include "radarslam/map/map_layers.h"

namespace radarslam {

inline constexpr const char* kLayersDir = "layers";
inline constexpr const char* kGridLayerFile = "grid.pgm";
inline constexpr const char* kGridYamlLayerFile = "grid.yaml";
inline constexpr const char* kGridOverviewLayerFile = "grid_overview.pgm";
inline constexpr const char* kGridTilesLayerFile = "grid_tiles.txt";
/// First line of layers/grid_tiles.txt.
inline constexpr const char* kGridTilesHeader = "radarslam grid tiles 1";
inline constexpr const char* kCloudLayerFile = "cloud.pcd";
inline constexpr const char* kCloudTilesLayerFile = "cloud_tiles.txt";
/// First line of layers/cloud_tiles.txt.
inline constexpr const char* kCloudTilesHeader = "radarslam cloud tiles 1";
inline constexpr const char* kOctomapLayerFile = "map.bt";

/// Grid image pixel of a cell: round(255 * (100 - cell) / 100) for 0..100, 205 for unknown (-1).
unsigned char gridPixel(int cell);
/// The cell of a pixel gridPixel() produces, -2 for any other pixel value.
int gridCellOfPixel(unsigned char pixel);

/// P5 PGM of grid cells (row 0 = lowest y): top image row = highest y, pixel =
/// round(255 * (100 - cell) / 100) for cells 0..100, 205 for unknown (-1).
std::string gridPgm(const std::vector<std::int8_t>& cells, std::uint32_t width, std::uint32_t height);
/// ROS map_server YAML for `image` (resolution as the float the message carries, origin exact).
std::string gridRosYaml(const std::string& image, float resolution, double origin_x, double origin_y);
/// PCD v0.7 (DATA binary, x y z intensity FLOAT32) of every keyframe point in the map frame; the
/// data section is byte for byte the PointCloud2 payload of dds::cloudMessage. `points` receives
/// the point count.
std::string cloudPcd(const KeyframeMap& map, std::uint64_t* points);
/// The header cloudPcd writes for `points` points.
std::string cloudPcdHeader(std::uint64_t points);
/// Bytes of one point's record in the cloud layer and the PointCloud2 payload: x y z intensity,
/// little-endian FLOAT32 (the PCD's and PointCloud2's point_step).
inline constexpr std::size_t kCloudRecordBytes = 16;
/// The data section of cloudPcd: kCloudRecordBytes (x y z intensity) per keyframe point, keyframe order.
std::vector<std::uint8_t> cloudPayload(const KeyframeMap& map);
/// One point's record of that payload: x, y in the map frame, z = 0, intensity = power, given
/// c = cos(kf.pose.phi), s = sin(kf.pose.phi). Every cloud writer goes through it (cloudPayload:
/// the layer, exportPointCloud, dds::cloudMessage; tiledCloudPayload), so all give identical floats.
inline void cloudRecord(const Keyframe& kf, double c, double s, const KeyframePoint& p, float out[4]) {
  out[0] = static_cast<float>(kf.pose.x + c * p.x - s * p.y);
  out[1] = static_cast<float>(kf.pose.y + s * p.x + c * p.y);
  out[2] = 0.f;
  out[3] = p.power;
}

/// Grid cells of layers/grid.pgm (checked against `entry` and the manifest's geometry).
std::vector<std::int8_t> readGridLayer(const std::filesystem::path& map_dir, const MapLayersManifest& layers);
/// Cells of layers/grid_overview.pgm (a tiled grid's overview; checked as readGridLayer).
std::vector<std::int8_t> readGridOverviewLayer(const std::filesystem::path& map_dir,
                                               const MapLayersManifest& layers);
/// The tile index of layers/grid_tiles.txt (checked against the manifest and the tiling).
std::vector<GridTileEntry> readGridTileIndexLayer(const std::filesystem::path& map_dir,
                                                  const MapLayersManifest& layers);
/// Streams the tiles of `index` out of layers/grid.pgm, one row of tiles (tile_cells image rows)
/// in memory at a time, never the whole grid: fn(entry, cells) for each, in the index's order.
/// Checks the file's size and header and each tile's cells against entry.sha256 (the whole
/// file's SHA-256 is not recomputed: every byte served is checked); throws InputError naming the
/// file and the tile.
void forEachGridTileLayer(
    const std::filesystem::path& map_dir, const MapLayersManifest& layers,
    const std::vector<GridTileEntry>& index,
    const std::function<void(const GridTileEntry&, const std::vector<std::int8_t>&)>& fn);
/// Payload (x y z intensity, 16 bytes per point) of layers/cloud.pcd; `points` = the count.
std::vector<std::uint8_t> readCloudLayer(const std::filesystem::path& map_dir,
                                         const MapLayersManifest& layers, std::uint64_t& points);
/// The cloud's tile index of layers/cloud_tiles.txt (a tiled map; checked against the manifest).
std::vector<CloudTileEntry> readCloudTileIndexLayer(const std::filesystem::path& map_dir,
                                                    const MapLayersManifest& layers);
/// Streams the tiles of `index` out of layers/cloud.pcd (one tile's points in memory at a time):
/// fn(entry, payload) in order, each checked against entry.sha256; throws InputError naming the
/// file and the tile.
void forEachCloudTileLayer(
    const std::filesystem::path& map_dir, const MapLayersManifest& layers,
    const std::vector<CloudTileEntry>& index,
    const std::function<void(const CloudTileEntry&, const std::vector<std::uint8_t>&)>& fn);
/// OcTree binary data (the .bt body) of layers/map.bt.
std::vector<std::int8_t> readOctomapLayer(const std::filesystem::path& map_dir,
                                          const MapLayersManifest& layers);

/// Reads a layer file: checks it is a regular file of entry.bytes bytes whose SHA-256 is
/// entry.sha256; returns the header lines up to and including the line `last_header_line`
/// (at most 64 lines / 4 KiB) and puts the rest into `body`.
template <class Byte>
std::string readLayerFile(const std::filesystem::path& map_dir, const LayerFileEntry& entry,
                          const std::string& last_header_line, std::vector<Byte>& body);

}  // namespace radarslam
