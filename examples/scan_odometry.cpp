// A program that uses radarslam as a library (find_package(radarslam CONFIG)): reads any radar
// dataset radarslam reads, prints each scan's stamp and geometry, and runs the RadarSLAM odometry
// front end on it.
//
//   scan_odometry DATASET_DIR [MAX_SCANS]
#include <radarslam/core/errors.h>
#include <radarslam/frontend/odometry.h>
#include <radarslam/io/dataset.h>
#include <radarslam/obs/registration.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: scan_odometry DATASET_DIR [MAX_SCANS]\n");
    return 2;
  }
  try {
    radarslam::registerRadarslamClasses();
    const auto reader = radarslam::openDataset(argv[1]);
    const std::size_t n =
        argc > 2 ? std::min<std::size_t>(std::strtoul(argv[2], nullptr, 10), reader->size()) : reader->size();
    radarslam::RadarOdometry odometry;
    for (std::size_t i = 0; i < n; ++i) {
      const auto scan = reader->readScan(i);
      const radarslam::OdometryStep step = odometry.process(*scan);
      std::printf("scan %zu stamp_ns %lld azimuths %u bins %u resolution_m %.5f x %.3f y %.3f yaw %.4f %s\n",
                  i, static_cast<long long>(step.stamp), scan->num_azimuths, scan->num_bins,
                  scan->range_resolution_m, step.pose.x, step.pose.y, step.pose.phi,
                  radarslam::toString(step.status));
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "scan_odometry: error: %s\n", radarslam::describeException(e).c_str());
    return 1;
  }
  return 0;
}
