#pragma once
// Decoding scans ahead of their consumer: a background thread reads scans [first, end) of a
// DatasetReader in order, up to `depth` ahead, and hands them out in the same order. A scan's
// decoding (PNG inflate, ~10 ms for an Oxford scan) then overlaps the consumer's work on it.
// Private to the io module; ScanIterator uses it when asked to prefetch.
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <string>
#include <thread>

#include "radarslam/io/dataset.h"

namespace radarslam::io_detail {

/// One scan as read and checked, or the error reading it raised (rethrown by the consumer).
struct FetchedScan {
  CObservationRadarScan::Ptr scan;
  std::string inconsistency;  ///< checkConsistency()'s complaint, empty when consistent
  bool blank = false;         ///< no return at all (all-zero power)
  std::exception_ptr error;   ///< what readScan threw (then scan is null)
};

/// Reads scan i and checks it; never throws (errors are captured).
FetchedScan fetchScan(const DatasetReader& reader, std::size_t i);

class ScanPrefetcher {
 public:
  /// Starts reading at `first`. depth >= 1: scans held ready at most. The reader's readScan must
  /// be safe to call from another thread than the one calling its other const members.
  ScanPrefetcher(const DatasetReader& reader, std::size_t first, std::size_t end, std::size_t depth);
  ~ScanPrefetcher();  ///< stops and joins the reading thread (reads in flight finish first)
  ScanPrefetcher(const ScanPrefetcher&) = delete;
  ScanPrefetcher& operator=(const ScanPrefetcher&) = delete;

  /// The next scan in order (first, first + 1, ...); waits for it. Call at most end - first times.
  FetchedScan take();

 private:
  void run(std::size_t first, std::size_t end);

  const DatasetReader& reader_;
  std::size_t depth_;
  std::mutex mutex_;
  std::condition_variable ready_, space_;
  std::deque<FetchedScan> items_;
  bool stop_ = false;
  std::thread worker_;
};

}  // namespace radarslam::io_detail
