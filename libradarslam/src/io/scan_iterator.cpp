#include <algorithm>
#include <string>
#include <vector>

#include "radarslam/core/errors.h"
#include "radarslam/core/log.h"
#include "radarslam/io/dataset.h"
#include "scan_prefetcher.h"

namespace radarslam {

namespace {

// Median interval between consecutive index stamps in [first, end) (0 if fewer than 2 scans or
// the index has no usable stamps). Index stamps need no decoding.
StampNs medianIndexInterval(const DatasetReader& reader, std::size_t first, std::size_t end) {
  std::vector<StampNs> d;
  try {
    d.reserve(end - first);
    for (std::size_t i = first + 1; i < end; ++i) {
      const StampNs dt = reader.indexStamp(i) - reader.indexStamp(i - 1);
      if (dt > 0) d.push_back(dt);
    }
  } catch (const InputError&) {
    return 0;
  }
  if (d.empty()) return 0;
  std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
  return d[d.size() / 2];
}

}  // namespace

ScanIterator::ScanIterator(const DatasetReader& reader, bool skip_bad_scans, std::size_t first,
                           std::size_t end, std::size_t prefetch)
    : reader_(reader), skip_(skip_bad_scans) {
  end_ = std::min(end, reader.size());
  first_ = std::min(first, end_);
  pos_ = first_;
  stats_.scan_period_ns = medianIndexInterval(reader, first_, end_);
  if (prefetch > 0 && end_ > first_)
    prefetcher_ = std::make_unique<io_detail::ScanPrefetcher>(reader, first_, end_, prefetch);
}

ScanIterator::~ScanIterator() = default;

CObservationRadarScan::Ptr ScanIterator::next() {
  while (pos_ < end_) {
    const std::size_t i = pos_++;
    try {
      io_detail::FetchedScan fetched = prefetcher_ ? prefetcher_->take() : io_detail::fetchScan(reader_, i);
      if (fetched.error) std::rethrow_exception(fetched.error);
      auto scan = std::move(fetched.scan);
      if (!fetched.inconsistency.empty())
        throw InputError(reader_.scanPath(i).string(), "inconsistent scan: " + fetched.inconsistency);
      const StampNs t = scan->refStampNs();
      if (have_last_stamp_ && t == last_stamp_) {  // a duplicated index entry: not an error
        ++skipped_;
        ++stats_.skipped_duplicate;
        logger().logFmt(mrpt::system::LVL_WARN, "skipping scan %zu (%s): duplicate of the previous scan", i,
                        reader_.scanPath(i).string().c_str());
        continue;
      }
      if (have_last_stamp_ && t < last_stamp_)
        throw InputError(reader_.scanPath(i).string(), "reference time " + std::to_string(t) +
                                                           " ns is not after the previous scan's (" +
                                                           std::to_string(last_stamp_) + " ns)");
      if (have_last_stamp_) {
        const StampNs dt = t - last_stamp_;
        stats_.largest_gap_ns = std::max(stats_.largest_gap_ns, dt);
        if (stats_.scan_period_ns > 0 && dt > stats_.scan_period_ns + stats_.scan_period_ns / 2) {
          ++stats_.time_gaps;
          logger().logFmt(mrpt::system::LVL_WARN, "time gap of %.3f s before scan %zu (scan period %.3f s)",
                          toSeconds(dt), i, toSeconds(stats_.scan_period_ns));
        }
      }
      if (fetched.blank) {
        ++stats_.blank;
        logger().logFmt(mrpt::system::LVL_WARN, "scan %zu (%s) is blank (no return at all)", i,
                        reader_.scanPath(i).string().c_str());
      }
      last_stamp_ = t;
      have_last_stamp_ = true;
      last_ = i;
      return scan;
    } catch (const InputError& e) {
      if (!skip_) throw;
      ++skipped_;
      ++stats_.skipped_unreadable;
      logger().logFmt(mrpt::system::LVL_WARN, "skipping bad scan %zu: %s", i, e.what());
    }
  }
  return nullptr;
}

}  // namespace radarslam
