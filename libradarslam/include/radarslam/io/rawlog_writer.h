#pragma once
// Writing radar scans to an MRPT .rawlog (gzip-compressed stream of serialized observations, the
// format CRawlog::saveToRawLogFile writes and openDataset()/CRawlog read back).
// Write into a temporary path and rename (see core/atomic_file.h writeFileAtomically).
#include <cstddef>
#include <filesystem>
#include <memory>

#include "radarslam/obs/CObservationRadarScan.h"

namespace radarslam {

class RawlogWriter {
 public:
  /// Creates/truncates `file`. gzip_level 0 (none) .. 9 (best); 1 is fastest. Throws InputError.
  explicit RawlogWriter(const std::filesystem::path& file, int gzip_level = 1);
  ~RawlogWriter();
  RawlogWriter(const RawlogWriter&) = delete;
  RawlogWriter& operator=(const RawlogWriter&) = delete;

  void write(const CObservationRadarScan& scan);
  /// Flushes and closes the file (also done by the destructor, which cannot report errors).
  void close();
  std::size_t count() const { return count_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::filesystem::path file_;
  std::size_t count_ = 0;
};

}  // namespace radarslam
