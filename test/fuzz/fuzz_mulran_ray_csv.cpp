// Fuzz target: a MulRan per-ray CSV scan (sensor_data/radar/ray/<t_ns>.csv) through readScanFile().
#include "fuzz_common.h"
#include "radarslam/io/dataset.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  radarslam::fuzz::quietLogger();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const auto file = radarslam::fuzz::scratchDir() / "ray" / "1564718976161407002.csv";
  radarslam::fuzz::writeFile(file, data, size);
  radarslam::fuzz::expectOnlyInputError([&] { (void)radarslam::readScanFile(file); });
  return 0;
}
