// Fuzz target: Oxford-style polar PNG scans (Oxford, MulRan polar_oxford_form, Boreas), decoded
// through readScanFile() in a scratch dataset of each layout (PNG chunk checks, libpng via
// OpenCV, the metadata columns, each reader's stamp checks).
#include "fuzz_common.h"
#include "png_fixup.h"
#include "radarslam/io/dataset.h"

namespace {
namespace fs = std::filesystem;
using radarslam::fuzz::scratchDir;

struct Layout {
  fs::path scan;  // the scan file the fuzzer's bytes are written to
};
std::vector<Layout> layouts;
}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  radarslam::fuzz::quietLogger();
  const fs::path root = scratchDir();
  radarslam::fuzz::writeText(root / "oxford" / "radar.timestamps", "1547120788016733 1\n");
  layouts.push_back({root / "oxford" / "radar" / "1547120788016733.png"});
  layouts.push_back({root / "mulran" / "polar_oxford_form" / "1564718976161407002.png"});
  fs::create_directories(root / "boreas" / "applanix");
  layouts.push_back({root / "boreas" / "radar" / "1606417230036848.png"});
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::vector<std::uint8_t> bytes = radarslam::fuzz::maybeFixPngCrcs(data, size);
  for (const auto& layout : layouts) {
    radarslam::fuzz::writeFile(layout.scan, bytes.data(), bytes.size());
    radarslam::fuzz::expectOnlyInputError([&] { (void)radarslam::readScanFile(layout.scan); });
  }
  return 0;
}
