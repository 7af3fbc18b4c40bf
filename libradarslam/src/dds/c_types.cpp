#include "c_types.h"

#include <algorithm>
#include <string>

namespace radarslam::dds::detail {

namespace {

char* view(const std::string& s) { return const_cast<char*>(s.c_str()); }

template <class Seq, class T>
void viewSeq(Seq& seq, const std::vector<T>& v) {
  using Elem = std::remove_pointer_t<decltype(seq._buffer)>;
  static_assert(sizeof(Elem) == sizeof(T));
  seq._maximum = seq._length = static_cast<std::uint32_t>(v.size());
  seq._buffer = reinterpret_cast<Elem*>(const_cast<T*>(v.data()));
  seq._release = false;
}

template <class T, class Seq>
std::vector<T> copySeq(const Seq& seq) {
  using Elem = std::remove_pointer_t<decltype(seq._buffer)>;
  static_assert(sizeof(Elem) == sizeof(T));
  std::vector<T> out(seq._length);
  if (seq._length > 0) std::copy_n(reinterpret_cast<const T*>(seq._buffer), seq._length, out.data());
  return out;
}

std::string copyStr(const char* s) { return s ? std::string(s) : std::string(); }

void toC(const TimeMsg& t, builtin_interfaces_msg_dds__Time_& out) {
  out.sec = t.sec;
  out.nanosec = t.nanosec;
}
TimeMsg fromC(const builtin_interfaces_msg_dds__Time_& in) { return {in.sec, in.nanosec}; }

void toC(const HeaderMsg& h, std_msgs_msg_dds__Header_& out) {
  toC(h.stamp, out.stamp);
  out.frame_id = view(h.frame_id);
}
HeaderMsg fromC(const std_msgs_msg_dds__Header_& in) { return {fromC(in.stamp), copyStr(in.frame_id)}; }

void toC(const PoseMsg& p, geometry_msgs_msg_dds__Pose_& out) {
  out.position = {p.x, p.y, p.z};
  out.orientation = {p.qx, p.qy, p.qz, p.qw};
}
PoseMsg fromC(const geometry_msgs_msg_dds__Pose_& in) {
  return {in.position.x,    in.position.y,    in.position.z,   in.orientation.x,
          in.orientation.y, in.orientation.z, in.orientation.w};
}

}  // namespace

// --- nav_msgs/OccupancyGrid -------------------------------------------------------------------
template <>
void toC(const OccupancyGridMsg& m, nav_msgs_msg_dds__OccupancyGrid_& out,
         std::vector<sensor_msgs_msg_dds__PointField_>&) {
  toC(m.header, out.header);
  toC(m.map_load_time, out.info.map_load_time);
  out.info.resolution = m.resolution;
  out.info.width = m.width;
  out.info.height = m.height;
  toC(m.origin, out.info.origin);
  viewSeq(out.data, m.data);
}
template <>
OccupancyGridMsg fromC(const nav_msgs_msg_dds__OccupancyGrid_& in) {
  OccupancyGridMsg m;
  m.header = fromC(in.header);
  m.map_load_time = fromC(in.info.map_load_time);
  m.resolution = in.info.resolution;
  m.width = in.info.width;
  m.height = in.info.height;
  m.origin = fromC(in.info.origin);
  m.data = copySeq<std::int8_t>(in.data);
  return m;
}

// --- sensor_msgs/PointCloud2 ------------------------------------------------------------------
template <>
void toC(const PointCloud2Msg& m, sensor_msgs_msg_dds__PointCloud2_& out,
         std::vector<sensor_msgs_msg_dds__PointField_>& storage) {
  toC(m.header, out.header);
  out.height = m.height;
  out.width = m.width;
  storage.clear();
  for (const auto& f : m.fields) storage.push_back({view(f.name), f.offset, f.datatype, f.count});
  out.fields._maximum = out.fields._length = static_cast<std::uint32_t>(storage.size());
  out.fields._buffer = storage.data();
  out.fields._release = false;
  out.is_bigendian = m.is_bigendian;
  out.point_step = m.point_step;
  out.row_step = m.row_step;
  viewSeq(out.data, m.data);
  out.is_dense = m.is_dense;
}
template <>
PointCloud2Msg fromC(const sensor_msgs_msg_dds__PointCloud2_& in) {
  PointCloud2Msg m;
  m.header = fromC(in.header);
  m.height = in.height;
  m.width = in.width;
  for (std::uint32_t i = 0; i < in.fields._length; ++i) {
    const auto& f = in.fields._buffer[i];
    m.fields.push_back({copyStr(f.name), f.offset, f.datatype, f.count});
  }
  m.is_bigendian = in.is_bigendian;
  m.point_step = in.point_step;
  m.row_step = in.row_step;
  m.data = copySeq<std::uint8_t>(in.data);
  m.is_dense = in.is_dense;
  return m;
}

// --- octomap_msgs/Octomap ---------------------------------------------------------------------
template <>
void toC(const OctomapMsg& m, octomap_msgs_msg_dds__Octomap_& out,
         std::vector<sensor_msgs_msg_dds__PointField_>&) {
  toC(m.header, out.header);
  out.binary = m.binary;
  out.id = view(m.id);
  out.resolution = m.resolution;
  viewSeq(out.data, m.data);
}
template <>
OctomapMsg fromC(const octomap_msgs_msg_dds__Octomap_& in) {
  OctomapMsg m;
  m.header = fromC(in.header);
  m.binary = in.binary;
  m.id = copyStr(in.id);
  m.resolution = in.resolution;
  m.data = copySeq<std::int8_t>(in.data);
  return m;
}

// --- geometry_msgs/PoseWithCovarianceStamped --------------------------------------------------
template <>
void toC(const PoseWithCovarianceStampedMsg& m, geometry_msgs_msg_dds__PoseWithCovarianceStamped_& out,
         std::vector<sensor_msgs_msg_dds__PointField_>&) {
  toC(m.header, out.header);
  toC(m.pose, out.pose.pose);
  std::copy(m.covariance.begin(), m.covariance.end(), out.pose.covariance);
}
template <>
PoseWithCovarianceStampedMsg fromC(const geometry_msgs_msg_dds__PoseWithCovarianceStamped_& in) {
  PoseWithCovarianceStampedMsg m;
  m.header = fromC(in.header);
  m.pose = fromC(in.pose.pose);
  std::copy_n(in.pose.covariance, 36, m.covariance.begin());
  return m;
}

// --- radarslam/MapInfo ------------------------------------------------------------------------
template <>
void toC(const MapInfoMsg& m, radarslam_msg_dds__MapInfo_& out,
         std::vector<sensor_msgs_msg_dds__PointField_>&) {
  toC(m.header, out.header);
  out.map_name = view(m.map_name);
  out.format_version = m.format_version;
  out.keyframes = m.keyframes;
  out.revision = m.revision;
  out.grid_sha256 = view(m.grid_sha256);
  out.manifest_sha256 = view(m.manifest_sha256);
  toC(m.created, out.created);
  out.grid_width = m.grid_width;
  out.grid_height = m.grid_height;
  out.tile_cells = m.tile_cells;
  out.tiles_x = m.tiles_x;
  out.tiles_y = m.tiles_y;
  viewSeq(out.tile_indices, m.tile_indices);
  viewSeq(out.tile_sha256, m.tile_sha256);
  out.overview_sha256 = view(m.overview_sha256);
  out.cloud_tile_count = m.cloud_tile_count;
  out.cloud_points = m.cloud_points;
  out.cloud_sha256 = view(m.cloud_sha256);
}
template <>
MapInfoMsg fromC(const radarslam_msg_dds__MapInfo_& in) {
  MapInfoMsg m;
  m.header = fromC(in.header);
  m.map_name = copyStr(in.map_name);
  m.format_version = in.format_version;
  m.keyframes = in.keyframes;
  m.revision = in.revision;
  m.grid_sha256 = copyStr(in.grid_sha256);
  m.manifest_sha256 = copyStr(in.manifest_sha256);
  m.created = fromC(in.created);
  m.grid_width = in.grid_width;
  m.grid_height = in.grid_height;
  m.tile_cells = in.tile_cells;
  m.tiles_x = in.tiles_x;
  m.tiles_y = in.tiles_y;
  m.tile_indices = copySeq<std::uint32_t>(in.tile_indices);
  m.tile_sha256 = copySeq<std::uint8_t>(in.tile_sha256);
  m.overview_sha256 = copyStr(in.overview_sha256);
  m.cloud_tile_count = in.cloud_tile_count;
  m.cloud_points = in.cloud_points;
  m.cloud_sha256 = copyStr(in.cloud_sha256);
  return m;
}

// --- radarslam/MapTile ------------------------------------------------------------------------
template <>
void toC(const MapTileMsg& m, radarslam_msg_dds__MapTile_& out,
         std::vector<sensor_msgs_msg_dds__PointField_>& storage) {
  toC(m.header, out.header);
  out.revision = m.revision;
  out.tile_x = m.tile_x;
  out.tile_y = m.tile_y;
  out.tile_cells = m.tile_cells;
  out.tile_count = m.tile_count;
  out.cells_sha256 = view(m.cells_sha256);
  toC(m.grid, out.grid, storage);
}
template <>
MapTileMsg fromC(const radarslam_msg_dds__MapTile_& in) {
  MapTileMsg m;
  m.header = fromC(in.header);
  m.revision = in.revision;
  m.tile_x = in.tile_x;
  m.tile_y = in.tile_y;
  m.tile_cells = in.tile_cells;
  m.tile_count = in.tile_count;
  m.cells_sha256 = copyStr(in.cells_sha256);
  m.grid = fromC<OccupancyGridMsg>(in.grid);
  return m;
}

// --- radarslam/MapFileChunk -------------------------------------------------------------------
template <>
void toC(const MapFileChunkMsg& m, radarslam_msg_dds__MapFileChunk_& out,
         std::vector<sensor_msgs_msg_dds__PointField_>&) {
  toC(m.header, out.header);
  out.map_name = view(m.map_name);
  out.revision = m.revision;
  out.manifest_sha256 = view(m.manifest_sha256);
  out.file_count = m.file_count;
  out.total_chunks = m.total_chunks;
  out.file_index = m.file_index;
  out.path = view(m.path);
  out.file_size = m.file_size;
  out.file_sha256 = view(m.file_sha256);
  out.chunk_index = m.chunk_index;
  out.chunk_count = m.chunk_count;
  out.offset = m.offset;
  viewSeq(out.data, m.data);
}
template <>
MapFileChunkMsg fromC(const radarslam_msg_dds__MapFileChunk_& in) {
  MapFileChunkMsg m;
  m.header = fromC(in.header);
  m.map_name = copyStr(in.map_name);
  m.revision = in.revision;
  m.manifest_sha256 = copyStr(in.manifest_sha256);
  m.file_count = in.file_count;
  m.total_chunks = in.total_chunks;
  m.file_index = in.file_index;
  m.path = copyStr(in.path);
  m.file_size = in.file_size;
  m.file_sha256 = copyStr(in.file_sha256);
  m.chunk_index = in.chunk_index;
  m.chunk_count = in.chunk_count;
  m.offset = in.offset;
  m.data = copySeq<std::uint8_t>(in.data);
  return m;
}

// --- radarslam/LocalizationStatus -------------------------------------------------------------
template <>
void toC(const LocalizationStatusMsg& m, radarslam_msg_dds__LocalizationStatus_& out,
         std::vector<sensor_msgs_msg_dds__PointField_>&) {
  toC(m.header, out.header);
  out.level = m.level;
  out.status = view(m.status);
  out.check = view(m.check);
  out.pose_published = m.pose_published;
  out.keyframe = m.keyframe;
  out.fit_score = m.fit_score;
  out.inliers = m.inliers;
  out.sigma_xy_m = m.sigma_xy_m;
  out.sigma_yaw_rad = m.sigma_yaw_rad;
  out.global_fixes = m.global_fixes;
}
template <>
LocalizationStatusMsg fromC(const radarslam_msg_dds__LocalizationStatus_& in) {
  LocalizationStatusMsg m;
  m.header = fromC(in.header);
  m.level = in.level;
  m.status = copyStr(in.status);
  m.check = copyStr(in.check);
  m.pose_published = in.pose_published;
  m.keyframe = in.keyframe;
  m.fit_score = in.fit_score;
  m.inliers = in.inliers;
  m.sigma_xy_m = in.sigma_xy_m;
  m.sigma_yaw_rad = in.sigma_yaw_rad;
  m.global_fixes = in.global_fixes;
  return m;
}

// --- radarslam/RadarScan ----------------------------------------------------------------------
template <>
void toC(const RadarScanMsg& m, radarslam_msg_dds__RadarScan_& out,
         std::vector<sensor_msgs_msg_dds__PointField_>&) {
  toC(m.header, out.header);
  out.num_azimuths = m.num_azimuths;
  out.num_bins = m.num_bins;
  out.range_resolution = m.range_resolution;
  out.range_offset = m.range_offset;
  viewSeq(out.azimuth_stamps_ns, m.azimuth_stamps_ns);
  viewSeq(out.azimuth_angles, m.azimuth_angles);
  viewSeq(out.azimuth_valid, m.azimuth_valid);
  viewSeq(out.power, m.power);
}
template <>
RadarScanMsg fromC(const radarslam_msg_dds__RadarScan_& in) {
  RadarScanMsg m;
  m.header = fromC(in.header);
  m.num_azimuths = in.num_azimuths;
  m.num_bins = in.num_bins;
  m.range_resolution = in.range_resolution;
  m.range_offset = in.range_offset;
  m.azimuth_stamps_ns = copySeq<std::int64_t>(in.azimuth_stamps_ns);
  m.azimuth_angles = copySeq<double>(in.azimuth_angles);
  m.azimuth_valid = copySeq<std::uint8_t>(in.azimuth_valid);
  m.power = copySeq<std::uint8_t>(in.power);
  return m;
}

}  // namespace radarslam::dds::detail
