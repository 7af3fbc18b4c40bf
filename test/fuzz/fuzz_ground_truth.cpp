// Fuzz targets for the ground-truth parsers, one program per format (RADARSLAM_FUZZ_GT selects):
//   1 Oxford gt/radar_odometry.csv   2 Boreas applanix/radar_poses.csv   3 MulRan global_pose.csv
//   4 RADIATE Navtech_Polar.txt (frame times), 5 Oxford radar.timestamps (scan index), both
//   through openDataset() on a scratch dataset folder.
#include "fuzz_common.h"
#include "radarslam/io/dataset.h"
#include "radarslam/io/ground_truth.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  radarslam::fuzz::quietLogger();
  std::filesystem::create_directories(radarslam::fuzz::scratchDir() / "radiate" / "Navtech_Polar");
  std::filesystem::create_directories(radarslam::fuzz::scratchDir() / "oxford" / "radar");
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace fuzz = radarslam::fuzz;
  const auto dir = fuzz::scratchDir();
#if RADARSLAM_FUZZ_GT == 1
  const auto file = dir / "radar_odometry.csv";
  fuzz::writeFile(file, data, size);
  fuzz::expectOnlyInputError([&] { (void)radarslam::readOxfordGroundTruth(file); });
#elif RADARSLAM_FUZZ_GT == 2
  const auto file = dir / "radar_poses.csv";
  fuzz::writeFile(file, data, size);
  fuzz::expectOnlyInputError([&] { (void)radarslam::readBoreasGroundTruth(file); });
#elif RADARSLAM_FUZZ_GT == 3
  const auto file = dir / "global_pose.csv";
  fuzz::writeFile(file, data, size);
  fuzz::expectOnlyInputError([&] { (void)radarslam::readMulRanGroundTruth(file); });
#elif RADARSLAM_FUZZ_GT == 4
  fuzz::writeFile(dir / "radiate" / "Navtech_Polar.txt", data, size);
  fuzz::expectOnlyInputError([&] {
    const auto reader = radarslam::openDataset(dir / "radiate");
    for (std::size_t i = 0; i < reader->size(); ++i) (void)reader->indexStamp(i);
  });
#elif RADARSLAM_FUZZ_GT == 5
  fuzz::writeFile(dir / "oxford" / "radar.timestamps", data, size);
  fuzz::expectOnlyInputError([&] {
    const auto reader = radarslam::openDataset(dir / "oxford");
    for (std::size_t i = 0; i < reader->size(); ++i) (void)reader->indexStamp(i);
  });
#else
#error "RADARSLAM_FUZZ_GT must be 1..5"
#endif
  return 0;
}
