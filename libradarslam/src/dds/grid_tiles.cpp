// Tiled grids over DDS (dds/grid_tiles.h).
#include "radarslam/dds/grid_tiles.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "radarslam/core/atomic_file.h"
#include "radarslam/core/errors.h"
#include "radarslam/dds/map_messages.h"
#include "radarslam/map/layer_files.h"
#include "radarslam/map/map_exports.h"
#include "radarslam/map/sha256.h"

namespace radarslam::dds {

namespace fs = std::filesystem;

namespace {

std::string cellsSha(const std::vector<std::int8_t>& cells) {
  return sha256Hex({reinterpret_cast<const unsigned char*>(cells.data()), cells.size()});
}

void pwriteAll(int fd, const void* data, std::size_t n, off_t at, const fs::path& file) {
  const char* p = static_cast<const char*>(data);
  while (n > 0) {
    const ssize_t w = ::pwrite(fd, p, n, at);
    if (w <= 0) throw InputError(file.string(), "write failed (disk full or no permission?)");
    p += w, n -= static_cast<std::size_t>(w), at += w;
  }
}

}  // namespace

OccupancyGridMsg overviewMessage(const fs::path& map_dir, const MapLayersManifest& layers, StampNs stamp) {
  OccupancyGridMsg g;
  g.header = {toTimeMsg(stamp), kMapFrame};
  g.map_load_time = toTimeMsg(stamp);
  g.resolution = static_cast<float>(layers.params.grid.resolution_m * layers.tiling.overview_factor);
  g.width = layers.tiling.overview_width;
  g.height = layers.tiling.overview_height;
  g.origin.x = layers.grid_origin_x;
  g.origin.y = layers.grid_origin_y;
  g.data = readGridOverviewLayer(map_dir, layers);
  return g;
}

OccupancyGridMsg overviewMessage(const OccupancyGridMsg& grid, const GridTiling& tiling) {
  OccupancyGridMsg g = grid;
  g.data = overviewCells(grid.data, tiling);
  g.resolution = static_cast<float>(static_cast<double>(grid.resolution) * tiling.overview_factor);
  g.width = tiling.overview_width;
  g.height = tiling.overview_height;
  return g;
}

void describeTiles(MapInfoMsg& info, const GridTiling& t, const std::vector<GridTileEntry>& index,
                   const std::string& overview_sha256) {
  info.grid_width = t.width;
  info.grid_height = t.height;
  info.tile_cells = t.tile_cells;
  info.tiles_x = t.tiles_x;
  info.tiles_y = t.tiles_y;
  info.tile_indices.clear();
  info.tile_sha256.clear();
  info.overview_sha256 = t.tiled() ? overview_sha256 : "";
  for (const auto& e : index) {
    info.tile_indices.push_back(t.tileKey(e.tx, e.ty));
    const auto bytes = sha256FromHex(e.sha256);
    if (!bytes) throw std::invalid_argument("describeTiles: tile index entry without a SHA-256");
    info.tile_sha256.insert(info.tile_sha256.end(), bytes->begin(), bytes->end());
  }
}

MapTileMsg tileMessage(const MapInfoMsg& info, const GridTiling& t, const GridTileEntry& entry,
                       std::vector<std::int8_t> cells, float resolution, double origin_x, double origin_y) {
  const TileRect r = tileRect(t, entry.tx, entry.ty);
  MapTileMsg m;
  m.header = info.header;
  m.revision = info.revision;
  m.tile_x = entry.tx;
  m.tile_y = entry.ty;
  m.tile_cells = t.tile_cells;
  m.tile_count = static_cast<std::uint32_t>(info.tile_indices.size());
  m.cells_sha256 = entry.sha256;
  m.grid.header = info.header;
  m.grid.map_load_time = info.header.stamp;
  m.grid.resolution = resolution;
  m.grid.width = r.cols;
  m.grid.height = r.rows;
  m.grid.origin.x = origin_x + r.col0 * static_cast<double>(resolution);
  m.grid.origin.y = origin_y + r.row0 * static_cast<double>(resolution);
  m.grid.data = std::move(cells);
  return m;
}

TiledGridWriter::TiledGridWriter(const fs::path& dir, const MapInfoMsg& info) : dir_(dir), info_(info) {
  GridTilingParams p;
  p.tile_cells = info.tile_cells;
  p.tile_above_cells = 0;
  tiling_ = gridTiling(info.grid_width, info.grid_height, p);
  const std::size_t n = info.tile_indices.size();
  if (info.tile_cells < 16 || info.grid_width == 0 || info.grid_height == 0 ||
      info.tile_sha256.size() != 32 * n || info.grid_sha256.size() != 64)
    throw InputError("MapInfo", "not a consistent description of a tiled grid");
  // The image is created at full size before any tile arrives: a hostile MapInfo must not make
  // it fill the disk.
  if (std::uint64_t{info.grid_width} * info.grid_height > kMaxLayerGridCells)
    throw InputError("MapInfo", "a grid of " + std::to_string(info.grid_width) + " x " +
                                    std::to_string(info.grid_height) +
                                    " cells is larger than any map layer (" +
                                    std::to_string(kMaxLayerGridCells) + " cells)");
  for (std::size_t i = 0; i < n; ++i)
    if (info.tile_indices[i] >= std::uint64_t{tiling_.tiles_x} * tiling_.tiles_y ||
        (i > 0 && info.tile_indices[i] <= info.tile_indices[i - 1]))
      throw InputError("MapInfo", "tile index out of range or not ascending");
  keys_ = info.tile_indices;
  expected_.assign(n, 0);
  tmp_ = dir_ / (".grid.pgm.tiles-" + std::to_string(::getpid()));
  fd_ = ::open(tmp_.c_str(), O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd_ < 0) throw InputError(tmp_.string(), "cannot create the grid image");
  const std::string header =
      "P5\n" + std::to_string(info.grid_width) + " " + std::to_string(info.grid_height) + "\n255\n";
  header_bytes_ = header.size();
  pwriteAll(fd_, header.data(), header.size(), 0, tmp_);
  // Every cell unknown until its tile arrives (tiles with no known cell are never sent).
  const std::vector<char> unknown(std::size_t{1} << 20, static_cast<char>(gridPixel(-1)));
  const std::uint64_t total = std::uint64_t{info.grid_width} * info.grid_height;
  for (std::uint64_t done = 0; done < total;) {
    const std::size_t k = static_cast<std::size_t>(std::min<std::uint64_t>(unknown.size(), total - done));
    pwriteAll(fd_, unknown.data(), k, static_cast<off_t>(header_bytes_ + done), tmp_);
    done += k;
  }
}

TiledGridWriter::~TiledGridWriter() {
  if (fd_ >= 0) ::close(fd_);
  if (!finished_) ::unlink(tmp_.c_str());  // our own temporary file only
}

bool TiledGridWriter::add(const MapTileMsg& tile) {
  if (!(tile.header.stamp == info_.header.stamp) || tile.revision != info_.revision) return false;
  const std::string what = "tile (" + std::to_string(tile.tile_x) + ", " + std::to_string(tile.tile_y) + ")";
  if (tile.tile_cells != tiling_.tile_cells || tile.tile_x >= tiling_.tiles_x ||
      tile.tile_y >= tiling_.tiles_y)
    throw InputError("MapTile", what + " is not a tile of the grid MapInfo describes");
  const std::uint32_t key = tiling_.tileKey(tile.tile_x, tile.tile_y);
  const auto it = std::lower_bound(keys_.begin(), keys_.end(), key);
  if (it == keys_.end() || *it != key) throw InputError("MapTile", what + " is not in MapInfo's tile index");
  const std::size_t i = static_cast<std::size_t>(it - keys_.begin());
  if (expected_[i]) return false;
  const TileRect r = tileRect(tiling_, tile.tile_x, tile.tile_y);
  if (tile.grid.width != r.cols || tile.grid.height != r.rows ||
      tile.grid.data.size() != std::size_t{r.cols} * r.rows || !(tile.grid.resolution > 0.f))
    throw InputError("MapTile",
                     what + ": expected " + std::to_string(r.cols) + "x" + std::to_string(r.rows) + " cells");
  const std::string sha = cellsSha(tile.grid.data);
  if (sha != toHex({info_.tile_sha256.data() + 32 * i, 32}))
    throw InputError("MapTile", what + ": SHA-256 of its cells differs from MapInfo's");
  if (resolution_ == 0) resolution_ = tile.grid.resolution;
  std::vector<char> row(r.cols);
  for (std::uint32_t k = 0; k < r.rows; ++k) {  // cell row row0 + k = image row height - 1 - (row0 + k)
    const std::int8_t* src = tile.grid.data.data() + std::size_t{k} * r.cols;
    for (std::uint32_t c = 0; c < r.cols; ++c) row[c] = static_cast<char>(gridPixel(src[c]));
    const std::uint64_t image_row = tiling_.height - 1 - (r.row0 + k);
    pwriteAll(fd_, row.data(), row.size(),
              static_cast<off_t>(header_bytes_ + image_row * tiling_.width + r.col0), tmp_);
  }
  expected_[i] = 1;
  ++received_;
  return true;
}

std::string TiledGridWriter::finish(double origin_x, double origin_y) {
  if (!complete())
    throw InputError(tmp_.string(), "incomplete: " + std::to_string(received_) + " of " +
                                        std::to_string(expected_.size()) + " tiles");
  // SHA-256 of the cells in message order (row 0 = lowest y = the image's last row).
  Sha256 sha;
  std::vector<char> px(tiling_.width);
  std::vector<std::int8_t> cells(tiling_.width);
  for (std::uint64_t row = 0; row < tiling_.height; ++row) {
    const std::uint64_t image_row = tiling_.height - 1 - row;
    if (::pread(fd_, px.data(), px.size(), static_cast<off_t>(header_bytes_ + image_row * tiling_.width)) !=
        static_cast<ssize_t>(px.size()))
      throw InputError(tmp_.string(), "read back failed");
    for (std::size_t c = 0; c < px.size(); ++c)
      cells[c] = static_cast<std::int8_t>(gridCellOfPixel(static_cast<unsigned char>(px[c])));
    sha.update({reinterpret_cast<const unsigned char*>(cells.data()), cells.size()});
  }
  const std::string got = sha.hexDigest();
  if (got != info_.grid_sha256)
    throw InputError(tmp_.string(),
                     "the tiles make a grid with SHA-256 " + got + ", MapInfo says " + info_.grid_sha256);
  if (::fsync(fd_) != 0) throw InputError(tmp_.string(), "fsync failed");
  ::close(fd_);
  fd_ = -1;
  char res[32];
  const auto [end, ec] = std::to_chars(res, res + sizeof res - 1, resolution_);
  *end = '\0';
  (void)ec;
  char yaml[512];
  std::snprintf(yaml, sizeof yaml,
                "image: grid.pgm\nmode: scale\nresolution: %s\norigin: [%.9g, %.9g, 0]\nnegate: 0\n"
                "occupied_thresh: 0.65\nfree_thresh: 0.196\n",
                res, origin_x, origin_y);
  writeTextAtomically(dir_ / "grid.yaml", yaml);
  fs::rename(tmp_, dir_ / "grid.pgm");
  finished_ = true;
  return got;
}

}  // namespace radarslam::dds
