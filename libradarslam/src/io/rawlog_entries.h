// The entries of an MRPT .rawlog, read without handing the file to arbitrary deserialisers.
//
// MRPT's CArchive::ReadObject() creates whatever registered class the file names and runs its
// deserialiser, and those trust every uint32 count of the file: a 30-byte rawlog naming an
// mrpt::obs::CSensoryFrame of 2^28 observations makes it allocate and zero 4 GiB (found by
// fuzz_rawlog, docs/hardening.md), any observation's sensor label can claim 4 GiB, and some
// classes open other files named inside the rawlog. So the object headers are parsed here and
// only an allow-list is read: radarslam::CObservationRadarScan (its own deserialiser bounds every
// size), mrpt::obs::CSensoryFrame (its body parsed here, growing only with observations actually
// read) and "nullptr" entries. Any other class is an InputError naming it.
#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "radarslam/obs/CObservationRadarScan.h"

namespace radarslam::io_detail {

class RawlogEntryStream {
 public:
  explicit RawlogEntryStream(const std::filesystem::path& file);
  ~RawlogEntryStream();
  /// The radar scans of the next entry (one for a scan, those of a sensory frame, none for a
  /// nullptr entry); nullopt at a clean end of file. Throws InputError if the file is truncated,
  /// corrupt, or holds an entry of a class outside the allow-list.
  std::optional<std::vector<CObservationRadarScan::Ptr>> next();
  std::size_t ordinal() const;  ///< number of entries read so far

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace radarslam::io_detail
