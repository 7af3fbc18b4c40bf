// The point cloud cut along the grid's tiles (map/cloud_tiles.h).
#include "radarslam/map/cloud_tiles.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

#include "radarslam/core/errors.h"
#include "radarslam/map/layer_files.h"
#include "radarslam/map/sha256.h"

namespace radarslam {

namespace {

std::uint32_t clampIndex(double v, std::uint32_t n) {
  if (!(v >= 0)) return 0;  // also NaN
  return v >= n ? n - 1 : static_cast<std::uint32_t>(v);
}
}  // namespace

std::uint32_t cloudTileKey(const GridTiling& t, double resolution, double origin_x, double origin_y, float x,
                           float y) {
  const double tile_m = t.tile_cells * resolution;
  return t.tileKey(clampIndex(std::floor((x - origin_x) / tile_m), t.tiles_x),
                   clampIndex(std::floor((y - origin_y) / tile_m), t.tiles_y));
}

TiledCloud tiledCloudPayload(const KeyframeMap& map, const GridTiling& t, double resolution, double origin_x,
                             double origin_y) {
  const std::size_t tiles = std::size_t{t.tiles_x} * t.tiles_y;
  std::vector<std::uint64_t> start(tiles + 1, 0);
  // Both passes compute each record the same way (cloudRecord), so the keys agree.
  auto forEachRecord = [&](auto&& f) {
    for (const auto& kf : map.keyframes) {
      const double c = std::cos(kf.pose.phi), s = std::sin(kf.pose.phi);
      for (const auto& p : kf.points) {
        float v[4];
        cloudRecord(kf, c, s, p, v);
        f(v, cloudTileKey(t, resolution, origin_x, origin_y, v[0], v[1]));
      }
    }
  };
  forEachRecord([&](const float*, std::uint32_t key) { ++start[key + 1]; });
  for (std::size_t k = 0; k < tiles; ++k) start[k + 1] += start[k];
  TiledCloud out;
  out.data.resize(start[tiles] * kCloudRecordBytes);
  std::vector<std::uint64_t> next(start.begin(), start.end() - 1);
  forEachRecord([&](const float* v, std::uint32_t key) {  // counting sort: stable
    std::memcpy(out.data.data() + next[key]++ * kCloudRecordBytes, v, kCloudRecordBytes);
  });
  for (std::size_t k = 0; k < tiles; ++k) {
    const std::uint64_t count = start[k + 1] - start[k];
    if (count == 0) continue;
    CloudTileEntry e;
    e.tx = static_cast<std::uint32_t>(k % t.tiles_x);
    e.ty = static_cast<std::uint32_t>(k / t.tiles_x);
    e.first = start[k];
    e.count = count;
    e.sha256 = sha256Hex({out.data.data() + e.first * kCloudRecordBytes, count * kCloudRecordBytes});
    out.tiles.push_back(std::move(e));
  }
  return out;
}

std::string cloudTileIndexText(const std::vector<CloudTileEntry>& tiles) {
  std::string out;
  for (const auto& e : tiles)
    out += std::to_string(e.tx) + " " + std::to_string(e.ty) + " " + std::to_string(e.first) + " " +
           std::to_string(e.count) + " " + e.sha256 + "\n";
  return out;
}

std::vector<CloudTileEntry> parseCloudTileIndex(const std::string& text, const GridTiling& t,
                                                std::uint64_t points, const std::string& origin) {
  std::vector<CloudTileEntry> out;
  std::istringstream in(text);
  std::string line;
  std::uint64_t next = 0;
  std::size_t n = 1;
  for (; std::getline(in, line); ++n) {
    std::istringstream ls(line);
    long long tx = -1, ty = -1, first = -1, count = -1;
    CloudTileEntry e;
    std::string rest;
    const bool ok = (ls >> tx >> ty >> first >> count >> e.sha256) && !(ls >> rest) && tx >= 0 && ty >= 0 &&
                    tx < t.tiles_x && ty < t.tiles_y && count > 0 && isSha256Hex(e.sha256);
    if (!ok)
      throw InputError(origin,
                       "line " + std::to_string(n) + ": expected 'tx ty first count sha256' of a tile");
    e.tx = static_cast<std::uint32_t>(tx);
    e.ty = static_cast<std::uint32_t>(ty);
    e.first = static_cast<std::uint64_t>(first);
    e.count = static_cast<std::uint64_t>(count);
    if (!out.empty() && t.tileKey(e.tx, e.ty) <= t.tileKey(out.back().tx, out.back().ty))
      throw InputError(origin, "line " + std::to_string(n) + ": tiles out of order or repeated");
    if (e.first != next || e.count > points - next)
      throw InputError(origin, "line " + std::to_string(n) + ": points " + std::to_string(e.first) + ".." +
                                   std::to_string(e.first + e.count) + " do not continue at " +
                                   std::to_string(next) + " within the cloud's " + std::to_string(points));
    next += e.count;
    out.push_back(std::move(e));
  }
  if (next != points)
    throw InputError(origin, "the tiles hold " + std::to_string(next) + " of the cloud's " +
                                 std::to_string(points) + " points");
  return out;
}

}  // namespace radarslam
