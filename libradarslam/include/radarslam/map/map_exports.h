#pragma once
// Exports of a KeyframeMap to formats other tools read. Every output file is written atomically.
//   grid      occupancy grid: PNG + PGM with a ROS map_server YAML each, MRPT .gridmap (gzip)
//   octomap   octomap::OcTree of the points as a slab at z = 0, free space carved from each
//             keyframe origin: .bt (binary, max-likelihood) and .ot (full probabilities)
//   cloud     all keyframe points in the map frame (x, y, z = 0, intensity = power): PLY, PCD
//   simplemap MRPT .simplemap: one CObservationPointCloud per keyframe at its pose
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "radarslam/map/keyframe_map.h"

namespace radarslam {

struct GridExportParams {
  double resolution_m = 0.2;
  double margin_m = 5.0;        ///< added around the points' bounding box
  double log_odds_hit = 0.85;   ///< per return in a cell (occupied evidence)
  double log_odds_miss = -0.4;  ///< per ray crossing a cell before its first return
  double log_odds_clamp = 3.5;
  /// Refuse absurd grids (InputError): 1e8 cells (4 km² at 0.2 m) for the single-image exports;
  /// the saved layers, tiled (map/grid_tiles.h), allow kMaxLayerGridCells.
  std::size_t max_cells = 100'000'000;
};

/// Occupancy as P(occupied) per cell, row 0 = lowest y; 0.5 = never observed.
struct OccupancyRaster {
  double x_min = 0, y_min = 0, resolution = 0.2;
  int width = 0, height = 0;
  std::vector<float> p_occupied;       ///< width*height, index = row * width + col
  std::vector<std::uint8_t> observed;  ///< 1 where a ray or a return reached the cell, same index
  float at(int col, int row) const { return p_occupied[static_cast<std::size_t>(row) * width + col]; }
};

/// Ray casts every keyframe: per azimuth sector (the map's num_azimuths) the cells from the sensor
/// up to the nearest return get a miss, every return cell gets a hit (radar returns several peaks
/// per azimuth, all of them are obstacles; the space beyond the first one is not known to be free).
OccupancyRaster buildOccupancy(const KeyframeMap& map, const GridExportParams& params = {});

/// Cells a tiled grid layer may have: 1e9 (40 km² at 0.2 m; building it takes 5 bytes per cell).
inline constexpr std::size_t kMaxLayerGridCells = 1'000'000'000;

/// The smallest multiple of params.resolution_m at which the map's grid has at most
/// params.max_cells cells (params.resolution_m itself for maps that fit).
double fittingGridResolution(const KeyframeMap& map, const GridExportParams& params);

/// Writes STEM.png, STEM.pgm, STEM.png.yaml, STEM.pgm.yaml (ROS map_server: image, resolution,
/// origin, negate 0, occupied_thresh 0.65, free_thresh 0.196; pixel = 255 * P(free)) and
/// STEM.gridmap (MRPT COccupancyGridMap2D, serialized, gzip) into `dir`. Returns the files.
std::vector<std::filesystem::path> exportOccupancyGrid(const KeyframeMap& map,
                                                       const std::filesystem::path& dir,
                                                       const std::string& stem = "grid",
                                                       const GridExportParams& params = {});

struct OctomapExportParams {
  /// How the voxels are filled (docs/maps.md, "OctoMap layer"):
  ///  grid_columns  the occupancy grid's cells (buildOccupancy at this resolution: free space up
  ///                to the nearest return per azimuth, every return occupied) lifted into the
  ///                one-voxel slab z in [0, resolution); the OcTree is encoded directly (no tree
  ///                in memory). The default: same evidence as the grid layer, ~100x faster.
  ///  point_rays    octomap::OcTree::insertPointCloud of every keyframe from its origin (rays to
  ///                every return, so free space is carved through nearer returns); slow.
  enum class Fill { grid_columns, point_rays };
  Fill fill = Fill::grid_columns;
  double resolution_m = 0.2;  ///< (0, 100] m; the map must fit OctoMap's 2^16 voxels per axis
  double max_range_m = -1.0;  ///< point_rays only: insertPointCloud max range (-1 = unlimited)
  /// point_rays only: refuse (InputError) trees whose rays would touch more voxels than this
  /// (estimated from the keyframes' bounding boxes), and maps farther than 32767 voxels from the
  /// origin (OctoMap keys). grid_columns is bounded by the grid's own cell limit and key check.
  std::size_t max_voxels = 100'000'000;
};
/// Writes STEM.bt (binary, max-likelihood) and STEM.ot (full log-odds) into `dir`.
std::vector<std::filesystem::path> exportOctomap(const KeyframeMap& map, const std::filesystem::path& dir,
                                                 const std::string& stem = "map",
                                                 const OctomapExportParams& params = {});

/// World-frame cloud of all keyframe points: STEM.ply (binary_little_endian, float x y z intensity)
/// and STEM.pcd (v0.7, DATA binary, fields x y z intensity).
std::vector<std::filesystem::path> exportPointCloud(const KeyframeMap& map, const std::filesystem::path& dir,
                                                    const std::string& stem = "cloud");

/// STEM.simplemap: per keyframe a CSensoryFrame with a CObservationPointCloud (CSimplePointsMap
/// in the sensor frame) at a CPose3DPDFGaussian of the keyframe pose.
std::vector<std::filesystem::path> exportSimpleMap(const KeyframeMap& map, const std::filesystem::path& dir,
                                                   const std::string& stem = "map");

}  // namespace radarslam
