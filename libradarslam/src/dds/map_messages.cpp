#include "radarslam/dds/map_messages.h"

#include <octomap/OcTree.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <unistd.h>
#include <atomic>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "radarslam/core/atomic_file.h"
#include "radarslam/core/errors.h"
#include "radarslam/map/layer_files.h"
#include "radarslam/map/octomap_slab.h"
#include "radarslam/map/sha256.h"

namespace radarslam::dds {

namespace fs = std::filesystem;

namespace {

HeaderMsg mapHeader(StampNs stamp) { return {toTimeMsg(stamp), kMapFrame}; }

// A private scratch directory, removed on scope exit (for the OctoMap export's files).
struct ScratchDir {
  fs::path path;
  ScratchDir() {
    static std::atomic<int> counter{0};
    path = fs::temp_directory_path() /
           ("radarslam-dds-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~ScratchDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
};

}  // namespace

OccupancyGridMsg gridMessage(const KeyframeMap& map, const GridExportParams& params, StampNs stamp) {
  return gridMessage(buildOccupancy(map, params), stamp);
}

OccupancyGridMsg gridMessage(const OccupancyRaster& r, StampNs stamp) {
  OccupancyGridMsg g;
  g.header = mapHeader(stamp);
  g.map_load_time = toTimeMsg(stamp);
  g.resolution = static_cast<float>(r.resolution);
  g.width = static_cast<std::uint32_t>(r.width);
  g.height = static_cast<std::uint32_t>(r.height);
  g.origin.x = r.x_min;
  g.origin.y = r.y_min;
  g.data = occupancyCells(r);
  return g;
}

OccupancyGridMsg gridMessage(const fs::path& map_dir, const MapLayersManifest& layers, StampNs stamp) {
  OccupancyGridMsg g;
  g.header = mapHeader(stamp);
  g.map_load_time = toTimeMsg(stamp);
  g.resolution = static_cast<float>(layers.params.grid.resolution_m);
  g.width = layers.grid_width;
  g.height = layers.grid_height;
  g.origin.x = layers.grid_origin_x;
  g.origin.y = layers.grid_origin_y;
  g.data = readGridLayer(map_dir, layers);
  return g;
}

PointCloud2Msg cloudMessage(const fs::path& map_dir, const MapLayersManifest& layers, StampNs stamp) {
  std::uint64_t n = 0;  // = the records' count: readCloudLayer checks the body against the manifest
  return cloudRecordsMessage(mapHeader(stamp), readCloudLayer(map_dir, layers, n));
}

OctomapMsg octomapMessage(const fs::path& map_dir, const MapLayersManifest& layers, StampNs stamp) {
  OctomapMsg m;
  m.header = mapHeader(stamp);
  m.binary = true;
  m.id = "OcTree";
  m.resolution = layers.params.octomap.resolution_m;
  m.data = readOctomapLayer(map_dir, layers);
  return m;
}

PointCloud2Msg cloudMessage(const KeyframeMap& map, StampNs stamp) {
  return cloudRecordsMessage(mapHeader(stamp), cloudPayload(map));  // the cloud layer's records
}

const std::vector<PointFieldMsg>& cloudRecordFields() {
  static const std::vector<PointFieldMsg> fields{{"x", 0}, {"y", 4}, {"z", 8}, {"intensity", 12}};
  return fields;
}

PointCloud2Msg cloudRecordsMessage(const HeaderMsg& header, std::vector<std::uint8_t> records) {
  PointCloud2Msg m;
  m.header = header;
  m.fields = cloudRecordFields();
  m.point_step = kCloudRecordBytes;
  m.width = static_cast<std::uint32_t>(records.size() / kCloudRecordBytes);
  m.row_step = m.width * m.point_step;
  m.data = std::move(records);
  return m;
}

OctomapMsg octomapMessage(const KeyframeMap& map, const OctomapExportParams& params, StampNs stamp) {
  OctomapMsg m;
  m.header = mapHeader(stamp);
  m.binary = true;
  m.id = "OcTree";
  m.resolution = params.resolution_m;
  std::string bytes;
  if (params.fill == OctomapExportParams::Fill::grid_columns) {
    GridExportParams grid;
    grid.resolution_m = params.resolution_m;
    return octomapMessage(buildOccupancy(map, grid), stamp);
  } else {
    ScratchDir scratch;
    exportOctomap(map, scratch.path, "map", params);
    octomap::OcTree tree(params.resolution_m);
    const fs::path bt = scratch.path / "map.bt";
    if (!tree.readBinary(bt.string())) throw InputError(bt.string(), "cannot read back the exported OctoMap");
    std::ostringstream os(std::ios::binary);
    tree.writeBinaryData(os);
    bytes = os.str();
  }
  m.data.assign(reinterpret_cast<const std::int8_t*>(bytes.data()),
                reinterpret_cast<const std::int8_t*>(bytes.data()) + bytes.size());
  return m;
}

OctomapMsg octomapMessage(const OccupancyRaster& raster, StampNs stamp) {
  OctomapSlabParams slab_params;
  slab_params.full_data = false;
  const std::string bytes = encodeOctomapSlab(raster, slab_params).binary_data;
  OctomapMsg m;
  m.header = mapHeader(stamp);
  m.binary = true;
  m.id = "OcTree";
  m.resolution = raster.resolution;
  m.data.assign(reinterpret_cast<const std::int8_t*>(bytes.data()),
                reinterpret_cast<const std::int8_t*>(bytes.data()) + bytes.size());
  return m;
}

std::string gridSha256(const OccupancyGridMsg& grid) {
  return sha256Hex({reinterpret_cast<const unsigned char*>(grid.data.data()), grid.data.size()});
}

std::vector<fs::path> writeGridFiles(const OccupancyGridMsg& grid, const fs::path& dir,
                                     const std::string& stem) {
  if (static_cast<std::uint64_t>(grid.width) * grid.height != grid.data.size() || grid.width == 0 ||
      grid.height == 0 || !(grid.resolution > 0.f))
    throw InputError("OccupancyGrid message", "inconsistent size " + std::to_string(grid.width) + "x" +
                                                  std::to_string(grid.height) + " with " +
                                                  std::to_string(grid.data.size()) + " cells");
  const int w = static_cast<int>(grid.width), h = static_cast<int>(grid.height);
  cv::Mat img(h, w, CV_8UC1);
  // Image row 0 = top = highest y (ROS map_server), pixel = 255 * P(free), 205 = unknown.
  for (int row = 0; row < h; ++row) {
    const std::int8_t* src = grid.data.data() + static_cast<std::size_t>(h - 1 - row) * w;
    auto* dst = img.ptr<unsigned char>(row);
    for (int col = 0; col < w; ++col) {
      const int v = src[col];
      dst[col] = v < 0 || v > 100 ? 205 : static_cast<unsigned char>(std::lround(255.0 * (100 - v) / 100.0));
    }
  }
  std::vector<fs::path> files;
  // PGM streamed from the image (no second copy of the grid in memory; same bytes as OpenCV's P5).
  const fs::path pgm = dir / (stem + ".pgm");
  writeFileAtomically(pgm, [&](const fs::path& tmp) {
    std::ofstream os(tmp, std::ios::binary);
    os << "P5\n" << w << ' ' << h << "\n255\n";
    for (int row = 0; row < h; ++row) os.write(img.ptr<char>(row), w);
    if (!os.flush()) throw InputError(pgm.string(), "cannot write the grid image");
  });
  files.push_back(pgm);
  const fs::path png = dir / (stem + ".png");
  std::vector<unsigned char> buf;
  if (!cv::imencode(".png", img, buf)) throw InputError(png.string(), "cannot encode the grid image");
  writeBytesAtomically(png, buf);
  files.push_back(png);
  // Rotation of the origin: yaw of the quaternion (our grids are axis-aligned: 0).
  const double yaw =
      std::atan2(2.0 * (grid.origin.qw * grid.origin.qz + grid.origin.qx * grid.origin.qy),
                 1.0 - 2.0 * (grid.origin.qy * grid.origin.qy + grid.origin.qz * grid.origin.qz));
  char res[32];
  const auto [end, ec] = std::to_chars(res, res + sizeof res - 1, grid.resolution);  // shortest round trip
  *end = '\0';
  (void)ec;
  char yaml[512];
  std::snprintf(yaml, sizeof yaml,
                "image: %s.pgm\nmode: scale\nresolution: %s\norigin: [%.9g, %.9g, %.9g]\nnegate: 0\n"
                "occupied_thresh: 0.65\nfree_thresh: 0.196\n",
                stem.c_str(), res, grid.origin.x, grid.origin.y, yaw);
  const fs::path yaml_path = dir / (stem + ".yaml");
  writeTextAtomically(yaml_path, yaml);
  files.push_back(yaml_path);
  return files;
}

void writePcdFile(const PointCloud2Msg& cloud, const fs::path& path) {
  const std::uint64_t n = static_cast<std::uint64_t>(cloud.width) * cloud.height;
  if (cloud.is_bigendian || cloud.fields.empty() || cloud.point_step == 0 ||
      n * cloud.point_step != cloud.data.size())
    throw InputError(path.string(), "inconsistent PointCloud2 message (size/point_step/endianness)");
  std::string names, sizes, types, counts;
  for (const auto& f : cloud.fields) {
    if (f.datatype != PointFieldMsg::kFloat32 || f.count != 1 || f.offset + 4 > cloud.point_step)
      throw InputError(path.string(), "PointCloud2 field '" + f.name + "' is not a single FLOAT32");
    names.append(" ").append(f.name);
    sizes.append(" 4");
    types.append(" F");
    counts.append(" 1");
  }
  std::string out = "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS";
  out.append(names).append("\nSIZE").append(sizes).append("\nTYPE").append(types).append("\nCOUNT").append(
      counts);
  out.append("\nWIDTH ")
      .append(std::to_string(cloud.width))
      .append("\nHEIGHT ")
      .append(std::to_string(cloud.height));
  out.append("\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS ").append(std::to_string(n)).append("\nDATA binary\n");
  const std::size_t header = out.size();
  out.resize(header + n * cloud.fields.size() * 4);
  char* dst = out.data() + header;
  for (std::uint64_t i = 0; i < n; ++i)
    for (const auto& f : cloud.fields) {
      std::memcpy(dst, cloud.data.data() + i * cloud.point_step + f.offset, 4);
      dst += 4;
    }
  writeTextAtomically(path, out);
}

void writeOctomapFile(const OctomapMsg& octomap, const fs::path& path) {
  if (!octomap.binary || octomap.id != "OcTree" || !(octomap.resolution > 0))
    throw InputError(path.string(), "Octomap message is not a binary OcTree (id '" + octomap.id + "')");
  // Checked and counted by walking the stream, never built into a tree (which costs ~80 bytes per
  // voxel: 600 MB for the demo map's 6.8 MB OctoMap).
  OctomapSlab slab;
  slab.resolution = octomap.resolution;
  slab.binary_data.assign(reinterpret_cast<const char*>(octomap.data.data()), octomap.data.size());
  const auto nodes = octreeBinaryNodeCount(slab.binary_data);
  if (!nodes) throw InputError(path.string(), "Octomap message data does not parse");
  slab.nodes = *nodes;
  writeTextAtomically(path, octomapBinaryFile(slab));
}

}  // namespace radarslam::dds
