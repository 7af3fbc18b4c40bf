// MRPT .simplemap export: keyframes as (CPose3DPDFGaussian, CSensoryFrame) pairs, each frame with
// one CObservationPointCloud of the keyframe's points (sensor frame), so MRPT tools (sm-cli,
// RawLogViewer, mp2p_icp) can rebuild maps from it. CSimpleMap::insert with a 2D PDF throws.
#include <mrpt/maps/CSimpleMap.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose3DPDFGaussian.h>

#include "radarslam/core/atomic_file.h"
#include "radarslam/core/errors.h"
#include "radarslam/map/map_exports.h"

namespace radarslam {
namespace fs = std::filesystem;

std::vector<fs::path> exportSimpleMap(const KeyframeMap& map, const fs::path& dir, const std::string& stem) {
  mrpt::maps::CSimpleMap sm;
  for (const auto& kf : map.keyframes) {
    auto pts = mrpt::maps::CSimplePointsMap::Create();
    pts->reserve(kf.points.size());
    for (const auto& p : kf.points) pts->insertPoint(p.x, p.y, 0.f);
    auto obs = mrpt::obs::CObservationPointCloud::Create();
    obs->pointcloud = pts;
    obs->timestamp = toMrptTime(kf.stamp_ns);
    obs->sensorLabel = "radar_peaks";
    auto sf = mrpt::obs::CSensoryFrame::Create();
    sf->insert(obs);
    auto pdf = mrpt::poses::CPose3DPDFGaussian::Create();
    pdf->mean = mrpt::poses::CPose3D(kf.pose.x, kf.pose.y, 0.0, kf.pose.phi, 0.0, 0.0);
    sm.insert(pdf, sf);
  }
  const fs::path path = dir / (stem + ".simplemap");
  writeFileAtomically(path, [&](const fs::path& tmp) {
    if (!sm.saveToFile(tmp.string())) throw InputError(path.string(), "cannot write the simplemap");
  });
  return {path};
}

}  // namespace radarslam
