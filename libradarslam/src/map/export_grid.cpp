// Occupancy grid export: our own log-odds ray caster (see buildOccupancy) copied into an MRPT
// COccupancyGridMap2D for .gridmap, and into 8-bit images with ROS map_server YAMLs.
//
// Why not COccupancyGridMap2D::insertObservation(CObservation2DRangeScan)? A 2D range scan holds
// one range per beam, but a radar keyframe has several returns per azimuth (the peak cloud of
// Algorithm 1 keeps every strong peak): converting would drop all but one return per azimuth.
// Casting rays ourselves keeps every return as an obstacle while carving free space only up to
// the nearest one, which is what the radar actually observed.
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/serialization/CArchive.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "radarslam/core/atomic_file.h"
#include "radarslam/core/errors.h"
#include "radarslam/map/map_exports.h"

namespace radarslam {
namespace fs = std::filesystem;

namespace {
struct Bounds {
  double xmin = std::numeric_limits<double>::max(), ymin = xmin, xmax = -xmin, ymax = -xmin;
};
// The bounding box of every keyframe and keyframe point in the map frame.
Bounds mapBounds(const KeyframeMap& map) {
  Bounds b;
  auto grow = [&](double x, double y) {
    b.xmin = std::min(b.xmin, x), b.xmax = std::max(b.xmax, x), b.ymin = std::min(b.ymin, y),
    b.ymax = std::max(b.ymax, y);
  };
  for (const auto& kf : map.keyframes) {
    grow(kf.pose.x, kf.pose.y);
    const double c = std::cos(kf.pose.phi), s = std::sin(kf.pose.phi);
    for (const auto& p : kf.points) grow(kf.pose.x + c * p.x - s * p.y, kf.pose.y + s * p.x + c * p.y);
  }
  return b;
}
double gridCells(const Bounds& b, double res, double margin) {
  const double x0 = std::floor((b.xmin - margin) / res) * res, y0 = std::floor((b.ymin - margin) / res) * res;
  return std::ceil((b.xmax + margin - x0) / res) * std::ceil((b.ymax + margin - y0) / res);
}
}  // namespace

double fittingGridResolution(const KeyframeMap& map, const GridExportParams& params) {
  if (map.keyframes.empty() || !(params.resolution_m > 0)) return params.resolution_m;
  const Bounds b = mapBounds(map);
  for (int k = 1;; ++k)
    if (gridCells(b, k * params.resolution_m, params.margin_m) <= static_cast<double>(params.max_cells))
      return k * params.resolution_m;
}

namespace {
// The cells one keyframe's rays touch, in a window over that keyframe's footprint, with a hit and
// a miss flag each: de-duplicates the keyframe's hits and misses without per-cell stamps over the
// whole map. Only the touched entries are cleared between keyframes (clear), so the cost is the
// rays', not the window's area.
class KeyframeWindow {
 public:
  static constexpr std::uint8_t kHit = 1, kMiss = 2;
  void reset(int col, int row) { c_min_ = c_max_ = col, r_min_ = r_max_ = row; }
  void grow(int col, int row) {
    c_min_ = std::min(c_min_, col), c_max_ = std::max(c_max_, col);
    r_min_ = std::min(r_min_, row), r_max_ = std::max(r_max_, row);
  }
  void allocate() {
    w_ = c_max_ - c_min_ + 1;
    const std::size_t n = static_cast<std::size_t>(w_) * (r_max_ - r_min_ + 1);
    if (flags_.size() < n) flags_.resize(n, 0);
  }
  std::size_t index(int col, int row) const {
    return static_cast<std::size_t>(row - r_min_) * w_ + static_cast<std::size_t>(col - c_min_);
  }
  int col(std::size_t i) const { return c_min_ + static_cast<int>(i % w_); }
  int row(std::size_t i) const { return r_min_ + static_cast<int>(i / w_); }
  /// Sets flag f of entry i; true when it was not set before.
  bool mark(std::size_t i, std::uint8_t f) {
    if (flags_[i] & f) return false;
    flags_[i] |= f;
    return true;
  }
  bool has(std::size_t i, std::uint8_t f) const { return (flags_[i] & f) != 0; }
  void clear(const std::vector<std::size_t>& touched) {
    for (std::size_t i : touched) flags_[i] = 0;
  }

 private:
  int c_min_ = 0, c_max_ = 0, r_min_ = 0, r_max_ = 0, w_ = 1;
  std::vector<std::uint8_t> flags_;
};
}  // namespace

OccupancyRaster buildOccupancy(const KeyframeMap& map, const GridExportParams& params) {
  if (!(params.resolution_m > 0)) throw InputError("grid export", "resolution must be > 0");
  const double res = params.resolution_m;
  const Bounds bounds = mapBounds(map);
  const double xmin = bounds.xmin, ymin = bounds.ymin, xmax = bounds.xmax, ymax = bounds.ymax;
  OccupancyRaster out;
  out.resolution = res;
  if (map.keyframes.empty()) return out;
  out.x_min = std::floor((xmin - params.margin_m) / res) * res;
  out.y_min = std::floor((ymin - params.margin_m) / res) * res;
  const double w = std::ceil((xmax + params.margin_m - out.x_min) / res);
  const double h = std::ceil((ymax + params.margin_m - out.y_min) / res);
  if (w * h > static_cast<double>(params.max_cells))
    throw InputError("grid export", "grid of " + std::to_string(static_cast<long long>(w)) + " x " +
                                        std::to_string(static_cast<long long>(h)) +
                                        " cells is too large; use a coarser --resolution");
  out.width = static_cast<int>(w);
  out.height = static_cast<int>(h);
  const std::size_t cells = static_cast<std::size_t>(out.width) * out.height;
  // Five bytes per cell: the log-odds (turned into the probability in place at the end) and the
  // observed flag.
  std::vector<float> log_odds(cells, 0.f);
  out.observed.assign(cells, 0);

  const std::uint32_t sectors = std::max<std::uint32_t>(map.meta.sensor.num_azimuths, 1);
  std::vector<float> nearest(sectors);
  std::vector<std::pair<int, int>> nearest_cell(sectors), point_cells;
  KeyframeWindow window;
  std::vector<std::size_t> misses, hits;  // window indices, each once
  auto cellOf = [&](double x, double y, int& col, int& row) {
    col = static_cast<int>(std::floor((x - out.x_min) / res));
    row = static_cast<int>(std::floor((y - out.y_min) / res));
    return col >= 0 && row >= 0 && col < out.width && row < out.height;
  };
  auto gridIndex = [&](std::size_t i, std::size_t& g) {  // false outside the grid
    const int col = window.col(i), row = window.row(i);
    g = static_cast<std::size_t>(row) * out.width + col;
    return col >= 0 && row >= 0 && col < out.width && row < out.height;
  };
  const auto clamp = static_cast<float>(params.log_odds_clamp);
  for (const auto& kf : map.keyframes) {
    int c0, r0;
    if (!cellOf(kf.pose.x, kf.pose.y, c0, r0)) continue;
    window.clear(misses);
    window.clear(hits);
    misses.clear();
    hits.clear();
    point_cells.clear();
    window.reset(c0, r0);
    std::fill(nearest.begin(), nearest.end(), std::numeric_limits<float>::infinity());
    const double c = std::cos(kf.pose.phi), s = std::sin(kf.pose.phi);
    for (const auto& p : kf.points) {
      const double wx = kf.pose.x + c * p.x - s * p.y, wy = kf.pose.y + s * p.x + c * p.y;
      int col, row;
      if (cellOf(wx, wy, col, row)) point_cells.emplace_back(col, row);
      window.grow(col, row);
      double a = std::atan2(p.y, p.x);
      if (a < 0) a += 2 * M_PI;
      const auto sector =
          std::min<std::uint32_t>(static_cast<std::uint32_t>(a / (2 * M_PI) * sectors), sectors - 1);
      const float r = std::hypot(p.x, p.y);
      if (r < nearest[sector]) nearest[sector] = r, nearest_cell[sector] = {col, row};
    }
    window.allocate();
    for (const auto& [col, row] : point_cells)
      if (const std::size_t i = window.index(col, row); window.mark(i, KeyframeWindow::kHit))
        hits.push_back(i);
    // Free space: cells from the sensor up to (excluding) the nearest return of each sector. The
    // segment joins two cells of the window, so each of its cells is in the window too.
    for (std::uint32_t k = 0; k < sectors; ++k) {
      if (!std::isfinite(nearest[k])) continue;
      const auto [c1, r1] = nearest_cell[k];
      // Bresenham from (c0, r0) to (c1, r1), excluding the end cell.
      int x = c0, y = r0;
      const int dx = std::abs(c1 - c0), dy = -std::abs(r1 - r0), sx = c0 < c1 ? 1 : -1, sy = r0 < r1 ? 1 : -1;
      int err = dx + dy;
      while (!(x == c1 && y == r1)) {
        if (const std::size_t i = window.index(x, y); window.mark(i, KeyframeWindow::kMiss))
          misses.push_back(i);
        const int e2 = 2 * err;
        if (e2 >= dy) err += dy, x += sx;
        if (e2 <= dx) err += dx, y += sy;
      }
    }
    std::size_t g;
    for (std::size_t i : misses) {
      if (!gridIndex(i, g)) continue;
      out.observed[g] = 1;
      // A cell with a return in this keyframe is not also free in it.
      if (!window.has(i, KeyframeWindow::kHit))
        log_odds[g] = std::max(-clamp, log_odds[g] + static_cast<float>(params.log_odds_miss));
    }
    for (std::size_t i : hits) {
      gridIndex(i, g);  // hits are grid cells
      out.observed[g] = 1;
      log_odds[g] = std::min(clamp, log_odds[g] + static_cast<float>(params.log_odds_hit));
    }
  }
  for (float& v : log_odds) v = 1.f / (1.f + std::exp(-v));
  out.p_occupied = std::move(log_odds);
  return out;
}

namespace {

std::string rosYaml(const std::string& image, const OccupancyRaster& r) {
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "image: %s\nresolution: %.9g\norigin: [%.9g, %.9g, 0.0]\nnegate: 0\noccupied_thresh: 0.65\n"
                "free_thresh: 0.196\n",
                image.c_str(), r.resolution, r.x_min, r.y_min);
  return buf;
}

void writeImage(const fs::path& path, const cv::Mat& img, const char* ext) {
  std::vector<unsigned char> bytes;
  if (!cv::imencode(ext, img, bytes)) throw InputError(path.string(), "image encoding failed");
  writeBytesAtomically(path, bytes);
}

}  // namespace

std::vector<fs::path> exportOccupancyGrid(const KeyframeMap& map, const fs::path& dir,
                                          const std::string& stem, const GridExportParams& params) {
  const OccupancyRaster r = buildOccupancy(map, params);
  if (r.width == 0)
    throw InputError(dir.string(), "cannot export an occupancy grid of a map without keyframes");
  // Image: row 0 at the top = highest y (ROS map_server), pixel = 255 * P(free) (negate 0).
  cv::Mat img(r.height, r.width, CV_8UC1);
  for (int row = 0; row < r.height; ++row)
    for (int col = 0; col < r.width; ++col)
      img.at<unsigned char>(r.height - 1 - row, col) =
          static_cast<unsigned char>(std::lround(255.0 * (1.0 - r.at(col, row))));
  std::vector<fs::path> files;
  for (const char* ext : {".png", ".pgm"}) {
    const fs::path image = dir / (stem + ext);
    writeImage(image, img, ext);
    const fs::path yaml = dir / (image.filename().string() + ".yaml");
    writeTextAtomically(yaml, rosYaml(image.filename().string(), r));
    files.push_back(image);
    files.push_back(yaml);
  }

  mrpt::maps::COccupancyGridMap2D grid;
  const double res = r.resolution;
  grid.setSize(static_cast<float>(r.x_min), static_cast<float>(r.x_min + r.width * res),
               static_cast<float>(r.y_min), static_cast<float>(r.y_min + r.height * res),
               static_cast<float>(res));
  for (int row = 0; row < r.height; ++row)
    for (int col = 0; col < r.width; ++col) {
      const int gx = grid.x2idx(r.x_min + (col + 0.5) * res), gy = grid.y2idx(r.y_min + (row + 0.5) * res);
      if (gx >= 0 && gy >= 0 && gx < static_cast<int>(grid.getSizeX()) &&
          gy < static_cast<int>(grid.getSizeY()))
        grid.setCell(gx, gy, 1.f - r.at(col, row));  // MRPT cells hold P(free)
    }
  const fs::path gridmap = dir / (stem + ".gridmap");
  writeFileAtomically(gridmap, [&](const fs::path& tmp) {
    mrpt::io::CFileGZOutputStream f;
    if (!f.open(tmp.string(), 1)) throw InputError(gridmap.string(), "cannot open for writing");
    auto arch = mrpt::serialization::archiveFrom(f);
    arch << grid;
    f.close();
  });
  files.push_back(gridmap);
  return files;
}

}  // namespace radarslam
