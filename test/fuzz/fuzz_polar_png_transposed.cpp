// Fuzz target: transposed polar PNG scans (rows = bins, columns = azimuths) of RADIATE
// (Navtech_Polar/) and MulRan (sensor_data/radar/polar/), through readScanFile().
#include "fuzz_common.h"
#include "png_fixup.h"
#include "radarslam/io/dataset.h"

namespace {
namespace fs = std::filesystem;
std::vector<fs::path> scans;
}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  radarslam::fuzz::quietLogger();
  const fs::path root = radarslam::fuzz::scratchDir();
  radarslam::fuzz::writeText(root / "radiate" / "Navtech_Polar.txt",
                             "Frame: 000001 Time: 1574859771.744660272\n"
                             "Frame: 000002 Time: 1574859771.977525228\n");
  scans.push_back(root / "radiate" / "Navtech_Polar" / "000001.png");
  scans.push_back(root / "mulran" / "sensor_data" / "radar" / "polar" / "1564718976161407002.png");
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::vector<std::uint8_t> bytes = radarslam::fuzz::maybeFixPngCrcs(data, size);
  for (const auto& scan : scans) {
    radarslam::fuzz::writeFile(scan, bytes.data(), bytes.size());
    radarslam::fuzz::expectOnlyInputError([&] { (void)radarslam::readScanFile(scan); });
  }
  return 0;
}
