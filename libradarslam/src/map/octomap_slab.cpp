#include "radarslam/map/octomap_slab.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <vector>

#include "radarslam/core/errors.h"

namespace radarslam {

namespace {

constexpr int kTreeDepth = 16;           // octomap::OcTree: 16 levels, keys 0..65535
constexpr long long kKeyOrigin = 32768;  // key of coordinate 0 (tree_max_val)

// octomap::logodds(): computed in double, stored as float, exactly as the OcTree stores them.
float logOdds(double p) { return static_cast<float>(std::log(p / (1 - p))); }

// "Is any cell observed" per key-aligned block of 2^level x 2^level cells.
struct Level {
  long long bx0 = 0, by0 = 0;
  long long w = 0, h = 0;
  std::vector<std::uint8_t> any;
  bool at(long long bx, long long by) const {
    bx -= bx0, by -= by0;
    return bx >= 0 && by >= 0 && bx < w && by < h && any[static_cast<std::size_t>(by * w + bx)] != 0;
  }
};

class SlabEncoder {
 public:
  SlabEncoder(const OccupancyRaster& r, const OctomapSlabParams& p, long long kx0, long long ky0)
      : r_(r),
        p_(p),
        kx0_(kx0),
        ky0_(ky0),
        clamp_min_(logOdds(p.clamp_min_probability)),
        clamp_max_(logOdds(p.clamp_max_probability)),
        occupied_(logOdds(p.occupied_probability)) {
    levels_.resize(kTreeDepth + 1);
    Level& l0 = levels_[0];
    l0.bx0 = kx0, l0.by0 = ky0, l0.w = r.width, l0.h = r.height;
    l0.any.assign(r.observed.begin(), r.observed.end());
    for (int k = 1; k <= kTreeDepth; ++k) {
      const Level& c = levels_[k - 1];
      Level& l = levels_[k];
      l.bx0 = c.bx0 >> 1, l.by0 = c.by0 >> 1;
      l.w = ((c.bx0 + c.w - 1) >> 1) - l.bx0 + 1;
      l.h = ((c.by0 + c.h - 1) >> 1) - l.by0 + 1;
      l.any.assign(static_cast<std::size_t>(l.w * l.h), 0);
      for (long long y = 0; y < c.h; ++y)
        for (long long x = 0; x < c.w; ++x)
          if (c.any[static_cast<std::size_t>(y * c.w + x)] != 0)
            l.any[static_cast<std::size_t>((((c.by0 + y) >> 1) - l.by0) * l.w +
                                           (((c.bx0 + x) >> 1) - l.bx0))] = 1;
    }
  }

  void encode(OctomapSlab& out) {
    if (!levels_[kTreeDepth].at(0, 0)) return;  // nothing observed: OctoMap writes no root
    out_ = &out;
    node(kTreeDepth, 0, 0);
  }

 private:
  float leafLogOdds(long long kx, long long ky) const {
    const std::size_t i = static_cast<std::size_t>((ky - ky0_) * r_.width + (kx - kx0_));
    const float prob = r_.p_occupied[i];
    const float l = std::log(prob / (1.0f - prob));
    return std::clamp(l, clamp_min_, clamp_max_);
  }

  // The node covering key block (bx, by) of `level` (level 16 = the root); returns its log-odds
  // (a leaf's own, an inner node's maximum over its children, as updateInnerOccupancy sets it).
  float node(int level, long long bx, long long by) {
    ++out_->nodes;
    const bool full = p_.full_data;
    std::size_t value_at = 0;
    if (full) {
      value_at = out_->full_data.size();
      out_->full_data.append(5, '\0');  // value (float), then the child mask
    }
    if (level == 0) {
      ++out_->leaves;
      const float v = leafLogOdds(bx, by);
      if (full) std::memcpy(&out_->full_data[value_at], &v, sizeof v);  // child mask stays 0
      return v;
    }
    // Children in OctoMap's order: index = x bit + 2 y bit + 4 z bit of the key at this depth.
    // The slab's z key (32768) has only the top bit set: z bit 1 at the root, 0 below.
    const int z = level == kTreeDepth ? 4 : 0;
    bool exists[8] = {};
    std::uint8_t mask = 0;
    std::uint16_t bits = 0;  // 2 bits per child: 01 free leaf, 10 occupied leaf, 11 inner node
    const std::size_t bits_at = out_->binary_data.size();
    out_->binary_data.append(2, '\0');
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        const long long cx = 2 * bx + i, cy = 2 * by + j;
        if (!levels_[level - 1].at(cx, cy)) continue;
        const int c = i + 2 * j + z;
        exists[c] = true;
        mask = static_cast<std::uint8_t>(mask | (1u << c));
        const unsigned code = level - 1 > 0 ? 3u : (leafLogOdds(cx, cy) > occupied_ ? 2u : 1u);
        bits = static_cast<std::uint16_t>(bits | (code << (2 * c)));
      }
    out_->binary_data[bits_at] = static_cast<char>(bits & 0xff);
    out_->binary_data[bits_at + 1] = static_cast<char>(bits >> 8);
    if (full) out_->full_data[value_at + 4] = static_cast<char>(mask);
    float max_child = -INFINITY;
    for (int c = 0; c < 8; ++c) {
      if (!exists[c]) continue;
      // Leaves appear in the binary stream only as their 2 bits above; node(0, ...) counts them
      // and writes their value to the full stream.
      max_child = std::max(max_child, node(level - 1, 2 * bx + (c & 1), 2 * by + ((c >> 1) & 1)));
    }
    if (full) std::memcpy(&out_->full_data[value_at], &max_child, sizeof max_child);
    return max_child;
  }

  const OccupancyRaster& r_;
  const OctomapSlabParams& p_;
  long long kx0_, ky0_;
  float clamp_min_, clamp_max_, occupied_;
  std::vector<Level> levels_;
  OctomapSlab* out_ = nullptr;
};

std::string header(const char* first_line, const OctomapSlab& slab) {
  std::ostringstream s;
  s << first_line << "\n# (feel free to add / change comments, but leave the first line as it is!)\n#\n";
  s << "id OcTree" << std::endl;
  s << "size " << slab.nodes << std::endl;
  s << "res " << slab.resolution << std::endl;
  s << "data" << std::endl;
  return s.str();
}

}  // namespace

OctomapSlab encodeOctomapSlab(const OccupancyRaster& r, const OctomapSlabParams& params) {
  OctomapSlab out;
  out.resolution = r.resolution;
  if (!(r.resolution > 0) || !std::isfinite(r.resolution))
    throw InputError("octomap export", "resolution must be a positive number");
  if (!(0 < params.clamp_min_probability && params.clamp_min_probability < params.occupied_probability &&
        params.occupied_probability < params.clamp_max_probability && params.clamp_max_probability < 1))
    throw InputError("octomap export", "need 0 < clamp_min < occupied < clamp_max < 1 probabilities");
  if (r.width <= 0 || r.height <= 0) return out;
  const double fx = r.x_min / r.resolution, fy = r.y_min / r.resolution;
  const long long kx0 = std::llround(fx) + kKeyOrigin, ky0 = std::llround(fy) + kKeyOrigin;
  if (std::abs(fx - std::round(fx)) > 1e-6 || std::abs(fy - std::round(fy)) > 1e-6)
    throw InputError("octomap export", "raster origin is not a multiple of the resolution");
  const long long max_key = (1LL << kTreeDepth) - 1;
  if (kx0 < 0 || ky0 < 0 || kx0 + r.width - 1 > max_key || ky0 + r.height - 1 > max_key) {
    std::ostringstream msg;
    msg << "the map spans x " << r.x_min << ".." << r.x_min + r.width * r.resolution << " m, y " << r.y_min
        << ".." << r.y_min + r.height * r.resolution << " m: beyond OctoMap's +-" << kKeyOrigin * r.resolution
        << " m at " << r.resolution << " m resolution (use a coarser resolution)";
    throw InputError("octomap export", msg.str());
  }
  if (r.observed.size() != static_cast<std::size_t>(r.width) * r.height ||
      r.p_occupied.size() != r.observed.size())
    throw InputError("octomap export", "raster has inconsistent sizes");
  SlabEncoder(r, params, kx0, ky0).encode(out);
  return out;
}

namespace {
// One inner node at `depth` (root 0): its child codes, then its inner children in order.
bool walkBinaryNode(std::string_view d, std::size_t& pos, std::size_t& nodes, int depth) {
  if (depth >= kTreeDepth || d.size() - pos < 2) return false;
  const unsigned codes = static_cast<unsigned char>(d[pos]) | static_cast<unsigned char>(d[pos + 1]) << 8;
  pos += 2;
  for (int i = 0; i < 8; ++i) nodes += ((codes >> (2 * i)) & 3u) != 0;  // 01 free, 10 occupied, 11 inner
  for (int i = 0; i < 8; ++i)
    if (((codes >> (2 * i)) & 3u) == 3u && !walkBinaryNode(d, pos, nodes, depth + 1)) return false;
  return true;
}
}  // namespace

std::optional<std::size_t> octreeBinaryNodeCount(std::string_view data) {
  if (data.empty()) return 0;      // an empty tree writes no data
  std::size_t pos = 0, nodes = 1;  // the root
  if (!walkBinaryNode(data, pos, nodes, 0) || pos != data.size()) return std::nullopt;
  return nodes;
}

std::string octomapBinaryFile(const OctomapSlab& slab) {
  return header("# Octomap OcTree binary file", slab) + slab.binary_data;
}

std::string octomapFullFile(const OctomapSlab& slab) {
  return header("# Octomap OcTree file", slab) + slab.full_data;
}

}  // namespace radarslam
