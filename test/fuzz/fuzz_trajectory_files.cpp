// Fuzz target: trajectory files (io/trajectory_files.h): the same bytes read as a TUM file, a
// KITTI file (auto-detected, TUM, KITTI) and a stamp file.
#include "fuzz_common.h"
#include "radarslam/io/trajectory_files.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  radarslam::fuzz::quietLogger();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace fuzz = radarslam::fuzz;
  static const auto file = fuzz::scratchDir() / "traj.txt";  // no companion .times.txt exists
  fuzz::writeFile(file, data, size);
  fuzz::expectOnlyInputError([&] { (void)radarslam::readTrajectoryFile(file); });
  fuzz::expectOnlyInputError([&] { (void)radarslam::readTumTrajectory(file); });
  fuzz::expectOnlyInputError([&] { (void)radarslam::readKittiTrajectory(file); });
  fuzz::expectOnlyInputError([&] { (void)radarslam::readStampFile(file); });
  radarslam::StampNs t = 0;
  const std::string text(reinterpret_cast<const char*>(data), std::min<std::size_t>(size, 64));
  (void)radarslam::parseStampText(text, t);  // must not throw at all
  return 0;
}
