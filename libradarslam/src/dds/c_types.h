#pragma once
// Private to the dds module: the idlc-generated C types and the mapping Msg <-> C type.
// Writing uses non-owning views (the C struct points into the C++ message); reading copies out of
// a loaned sample.
#include <dds/dds.h>

#include <vector>

#include "builtin_interfaces/msg/Time.h"
#include "geometry_msgs/msg/Pose.h"
#include "nav_msgs/msg/OccupancyGrid.h"
#include "octomap_msgs/msg/Octomap.h"
#include "radarslam/dds/messages.h"
#include "radarslam/msg/LocalizationStatus.h"
#include "radarslam/msg/MapFileChunk.h"
#include "radarslam/msg/MapInfo.h"
#include "radarslam/msg/MapTile.h"
#include "radarslam/msg/RadarScan.h"
#include "sensor_msgs/msg/PointCloud2.h"
#include "std_msgs/msg/Header.h"

namespace radarslam::dds::detail {

template <class Msg>
struct CType;

#define RADARSLAM_DDS_CTYPE(MSG, CTYPE)                                         \
  template <>                                                                   \
  struct CType<MSG> {                                                           \
    using type = CTYPE;                                                         \
    static const dds_topic_descriptor_t* descriptor() { return &CTYPE##_desc; } \
  }

RADARSLAM_DDS_CTYPE(OccupancyGridMsg, nav_msgs_msg_dds__OccupancyGrid_);
RADARSLAM_DDS_CTYPE(PointCloud2Msg, sensor_msgs_msg_dds__PointCloud2_);
RADARSLAM_DDS_CTYPE(OctomapMsg, octomap_msgs_msg_dds__Octomap_);
RADARSLAM_DDS_CTYPE(PoseWithCovarianceStampedMsg, geometry_msgs_msg_dds__PoseWithCovarianceStamped_);
RADARSLAM_DDS_CTYPE(MapInfoMsg, radarslam_msg_dds__MapInfo_);
RADARSLAM_DDS_CTYPE(RadarScanMsg, radarslam_msg_dds__RadarScan_);
RADARSLAM_DDS_CTYPE(LocalizationStatusMsg, radarslam_msg_dds__LocalizationStatus_);
RADARSLAM_DDS_CTYPE(MapFileChunkMsg, radarslam_msg_dds__MapFileChunk_);
RADARSLAM_DDS_CTYPE(MapTileMsg, radarslam_msg_dds__MapTile_);
#undef RADARSLAM_DDS_CTYPE

/// Fills `out` as a view of `msg` (valid while msg and `storage` live).
template <class Msg>
void toC(const Msg& msg, typename CType<Msg>::type& out,
         std::vector<sensor_msgs_msg_dds__PointField_>& storage);
/// Deep copy out of a received sample.
template <class Msg>
Msg fromC(const typename CType<Msg>::type& in);

}  // namespace radarslam::dds::detail
