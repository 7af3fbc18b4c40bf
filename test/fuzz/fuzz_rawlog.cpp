// Fuzz target: MRPT .rawlog files (gzip or plain MRPT serialization) through openDataset(), then
// every indexed scan read back.
#include "fuzz_common.h"
#include "radarslam/io/dataset.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  radarslam::fuzz::quietLogger();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const auto file = radarslam::fuzz::scratchDir() / "fuzz.rawlog";
  radarslam::fuzz::writeFile(file, data, size);
  radarslam::fuzz::expectOnlyInputError([&] {
    const auto reader = radarslam::openDataset(file);
    for (std::size_t i = 0; i < reader->size(); ++i) (void)reader->readScan(i);
  });
  return 0;
}
