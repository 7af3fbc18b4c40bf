#include <algorithm>
#include <string>

#include "radarslam/core/errors.h"
#include "radarslam/core/log.h"
#include "radarslam/io/dataset.h"

namespace radarslam {

ScanIterator::ScanIterator(const DatasetReader& reader, bool skip_bad_scans, std::size_t first,
                           std::size_t end)
    : reader_(reader), skip_(skip_bad_scans) {
  end_ = std::min(end, reader.size());
  first_ = std::min(first, end_);
  pos_ = first_;
}

CObservationRadarScan::Ptr ScanIterator::next() {
  while (pos_ < end_) {
    const std::size_t i = pos_++;
    try {
      auto scan = reader_.readScan(i);
      if (const std::string why = scan->checkConsistency(); !why.empty())
        throw InputError(reader_.scanPath(i).string(), "inconsistent scan: " + why);
      const StampNs t = scan->refStampNs();
      if (have_last_stamp_ && t <= last_stamp_)
        throw InputError(reader_.scanPath(i).string(), "reference time " + std::to_string(t) +
                                                           " ns is not after the previous scan's (" +
                                                           std::to_string(last_stamp_) + " ns)");
      last_stamp_ = t;
      have_last_stamp_ = true;
      last_ = i;
      return scan;
    } catch (const InputError& e) {
      if (!skip_) throw;
      ++skipped_;
      logger().logFmt(mrpt::system::LVL_WARN, "skipping bad scan %zu: %s", i, e.what());
    }
  }
  return nullptr;
}

}  // namespace radarslam
